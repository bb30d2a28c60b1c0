"""Reads the point fields of a PeriAdapt VTU snapshot (raw appended data, UInt64 headers)."""
import re
import struct


def read_vtu(path):
    """Returns {name: list of tuples (or floats for one component)}, with 'Points' among them."""
    data = open(path, 'rb').read()
    head_end = data.index(b'<AppendedData')
    header = data[:head_end].decode('ascii', 'replace')
    raw = data.index(b'_', head_end) + 1
    fields = {}
    for m in re.finditer(r'<DataArray ([^>]*)/?>', header):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        if attrs.get('format') != 'appended' or attrs['type'] != 'Float64':
            continue
        off = raw + int(attrs['offset'])
        nbytes = struct.unpack_from('<Q', data, off)[0]
        vals = struct.unpack_from('<%dd' % (nbytes // 8), data, off + 8)
        nc = int(attrs.get('NumberOfComponents', '1'))
        fields[attrs['Name']] = list(vals) if nc == 1 else [vals[i:i + nc] for i in range(0, len(vals), nc)]
    return fields


def last_snapshot(run_dir):
    import glob
    files = sorted(glob.glob(run_dir + '/snapshot_*.vtu'))
    return files[-1] if files else None
