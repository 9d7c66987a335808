#!/usr/bin/python3
"""Makes the fuzzing base folders and seed corpora (tests/fuzz/base, tests/fuzz/corpus).

Usage: make_seeds.py SURVEY_BUNDLE SONAR_SEQUENCE
  SURVEY_BUNDLE   a simulated survey bundle, e.g.
                  hullinspect-cli simulate --preset demo --out demo --start 10 --end 12 --half-width 1 --write-landmarks
  SONAR_SEQUENCE  a simulated acoustic sequence, e.g.
                  hullinspect-cli simulate --preset sonar-prism --out prism

The bundle is cut to its first keyframes (and the sequence to its first
steps) so every file is a few hundred bytes to a few kB: the harnesses read a
whole bundle per input, so small bases keep executions fast. Meshes and
PNG images are hand-made here; the JPEG seeds (corpus/image/*.jpg, OpenCV
cv::imwrite of random 6x8 grey and 4x5 colour images at quality 50), the
16-bit PNG and the STEP seed (corpus/mesh_step/cyl.step, OpenCASCADE's
STEPControl_Writer of a 0.5 x 1 m cylinder) were written once by a few lines
of C++ and are kept as they are. Re-running rewrites the other seeds.
"""
import gzip, json, os, shutil, struct, sys, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
KEYFRAMES = 6   # keyframes kept in the survey base
STEPS = 4       # steps kept in the sonar base


def lines(path):
    with open(path) as f:
        return f.read().splitlines()


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(path, mode) as f:
        f.write(data)


def keep(rows, pred, limit=None):
    out = [rows[0]] + [r for r in rows[1:] if pred(r.split(','))]
    return out[: limit + 1] if limit else out


def survey(src):
    base = os.path.join(HERE, 'base', 'survey')
    shutil.rmtree(base, ignore_errors=True)
    man = json.load(open(os.path.join(src, 'survey.json')))
    # The prior mesh, cut to the stretch the kept keyframes see, so the
    # harnesses can run the whole validate -> align -> adjust path
    # (issue 14) at a few milliseconds per input; the mesh readers are
    # fuzzed on their own.
    man['model_hint'] = 'hull.ply'
    files = {'survey.json': json.dumps(man, indent=2) + '\n'}
    kf = lambda r: int(r[0]) < KEYFRAMES
    files['nav.csv'] = keep(lines(os.path.join(src, 'nav.csv')), kf)
    files['odometry.csv'] = keep(lines(os.path.join(src, 'odometry.csv')), lambda r: int(r[1]) < KEYFRAMES)
    files['dvl.csv'] = keep(lines(os.path.join(src, 'dvl.csv')), kf)
    feats = keep(lines(os.path.join(src, 'features.csv')), kf, 24)
    files['features.csv'] = feats
    used = {r.split(',')[1] for r in feats[1:]}
    files['landmarks.csv'] = keep(lines(os.path.join(src, 'landmarks.csv')), lambda r: r[0] in used)
    files['truth/poses.csv'] = keep(lines(os.path.join(src, 'truth', 'poses.csv')), kf)
    files['truth/landmarks.csv'] = keep(lines(os.path.join(src, 'truth', 'landmarks.csv')), lambda r: r[0] in used)
    for name in ('model_pose.json', 'servo_to_top.json'):
        files['truth/' + name] = open(os.path.join(src, 'truth', name)).read()
    for name, rows in files.items():
        text = rows if isinstance(rows, str) else '\n'.join(rows) + '\n'
        write(os.path.join(base, name), text)
    x_gM = json.load(open(os.path.join(src, 'truth', 'model_pose.json')))['x_gM']
    marks = [list(map(float, r.split(',')[1:4])) for r in files['truth/landmarks.csv'][1:]]
    write(os.path.join(base, 'hull.ply'), crop_ply(os.path.join(src, man.get('model_hint', 'hull.ply')), x_gM, marks))
    return base


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll), as core/geometry/pose.h."""
    import numpy as np
    cr, sr, cp, sp, cy, sy = (np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw))
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx


def crop_ply(path, x_gM, points_g, margin=2.0):
    """The faces of a binary little-endian PLY (as HullInspect writes it: float
    or double x y z, then a uchar/int face list) whose vertices all lie within
    `margin` of the bounding box of points_g (global frame), as binary PLY."""
    import numpy as np
    data = open(path, 'rb').read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode().splitlines()
    nv = nf = 0
    vprops = []
    for line in header:
        t = line.split()
        if t[:2] == ['element', 'vertex']:
            nv = int(t[2])
        elif t[:2] == ['element', 'face']:
            nf = int(t[2])
        elif t[0] == 'property' and t[1] != 'list' and nf == 0:
            vprops.append((t[2], {'float': '<f4', 'double': '<f8'}[t[1]]))
    assert 'binary_little_endian' in header[1], path + ': binary little-endian PLY expected'
    vt = np.dtype(vprops)
    verts = np.frombuffer(data, vt, nv, end)
    xyz = np.stack([verts['x'], verts['y'], verts['z']], 1).astype(float)
    faces = np.frombuffer(data, np.dtype([('n', 'u1'), ('i', '<i4', 3)]), nf, end + nv * vt.itemsize)['i']
    g = xyz @ rotation(*x_gM[3:]).T + np.array(x_gM[:3])
    lo = np.min(points_g, 0) - margin
    hi = np.max(points_g, 0) + margin
    inside = np.all((g >= lo) & (g <= hi), 1)
    faces = faces[np.all(inside[faces], 1)]
    used = np.unique(faces)
    remap = np.full(nv, -1)
    remap[used] = np.arange(len(used))
    out = ('ply\nformat binary_little_endian 1.0\ncomment the fuzzing base: %s cut to the kept keyframes\n'
           'element vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
           'element face %d\nproperty list uchar int vertex_indices\nend_header\n'
           % (os.path.basename(path), len(used), len(faces))).encode()
    out += xyz[used].astype('<f4').tobytes()
    rows = np.zeros(len(faces), np.dtype([('n', 'u1'), ('i', '<i4', 3)]))
    rows['n'] = 3
    rows['i'] = remap[faces]
    return out + rows.tobytes()


def sonar(src):
    base = os.path.join(HERE, 'base', 'sonar')
    shutil.rmtree(base, ignore_errors=True)
    files = {'sonar.json': open(os.path.join(src, 'sonar.json')).read()}
    files['controls.csv'] = keep(lines(os.path.join(src, 'controls.csv')), lambda r: int(r[0]) < STEPS)
    files['measurements.csv'] = keep(lines(os.path.join(src, 'measurements.csv')), lambda r: int(r[0]) < STEPS)
    files['truth/poses.csv'] = keep(lines(os.path.join(src, 'truth', 'poses.csv')), lambda r: int(r[0]) < STEPS)
    files['truth/features.csv'] = lines(os.path.join(src, 'truth', 'features.csv'))
    for name, rows in files.items():
        text = rows if isinstance(rows, str) else '\n'.join(rows) + '\n'
        write(os.path.join(base, name), text)
    return base


def seeds_from_base(base, harness_of_file):
    """Seeds per file: the base file, and the base file cut after 1/3 and 2/3."""
    for name, harness in harness_of_file.items():
        data = open(os.path.join(base, name), 'rb').read()
        out = os.path.join(HERE, 'corpus', harness)
        shutil.rmtree(out, ignore_errors=True)
        write(os.path.join(out, 'full'), data)
        write(os.path.join(out, 'cut-third'), data[: len(data) // 3])
        write(os.path.join(out, 'cut-two-thirds'), data[: 2 * len(data) // 3])


# ---- hand-made meshes: a tetrahedron in every format --------------------
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def stl_ascii():
    s = 'solid tet\n'
    for f in F:
        s += ' facet normal 0 0 0\n  outer loop\n'
        for i in f:
            s += '   vertex %g %g %g\n' % V[i]
        s += '  endloop\n endfacet\n'
    return (s + 'endsolid tet\n').encode()


def stl_binary():
    b = b'tet'.ljust(80, b' ') + struct.pack('<I', len(F))
    for f in F:
        b += struct.pack('<3f', 0, 0, 0)
        for i in f:
            b += struct.pack('<3f', *V[i])
        b += b'\0\0'
    return b


def ply_ascii(extra=''):
    s = 'ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n'
    s += extra and 'property float deviation\n'
    s += 'element face 4\nproperty list uchar int vertex_indices\nend_header\n'
    for v in V:
        s += '%g %g %g%s\n' % (v + ((' 0.5',) if extra else ('',)))
    for f in F:
        s += '3 %d %d %d\n' % f
    return s.encode()


def ply_binary():
    h = ('ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n'
         'property float z\nelement face 4\nproperty list uchar uint vertex_indices\nend_header\n').encode()
    for v in V:
        h += struct.pack('<3f', *v)
    for f in F:
        h += struct.pack('<B3I', 3, *f)
    return h


def obj():
    s = '# tetrahedron\n' + ''.join('v %g %g %g\n' % v for v in V)
    s += 'vn 0 0 1\nvt 0 0\n'
    s += ''.join('f %d/1/1 %d/1/1 %d/1/1\n' % tuple(i + 1 for i in f) for f in F)
    s += 'f 1 2 3 4\n'  # a quad, triangulated
    return s.encode()


def off():
    s = 'OFF\n# tetrahedron\n4 5 0\n' + ''.join('%g %g %g\n' % v for v in V)
    return (s + ''.join('3 %d %d %d\n' % f for f in F) + '4 0 1 2 3\n').encode()


def gltf():
    pos = b''.join(struct.pack('<3f', *v) for v in V)
    idx = b''.join(struct.pack('<3H', *f) for f in F)
    buf = pos + idx
    import base64
    doc = {
        'asset': {'version': '2.0'},
        'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0}],
        'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1}]}],
        'buffers': [{'byteLength': len(buf),
                     'uri': 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()}],
        'bufferViews': [{'buffer': 0, 'byteOffset': 0, 'byteLength': len(pos)},
                        {'buffer': 0, 'byteOffset': len(pos), 'byteLength': len(idx)}],
        'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': 4, 'type': 'VEC3',
                       'min': [0, 0, 0], 'max': [1, 1, 1]},
                      {'bufferView': 1, 'componentType': 5123, 'count': 12, 'type': 'SCALAR'}],
    }
    return json.dumps(doc).encode()


def png(width, height, colour):
    raw = b''.join(b'\0' + bytes((x * 37 + y * 11) % 256 for x in range(width * (3 if colour else 1)))
                   for y in range(height))
    chunk = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    ihdr = struct.pack('>IIBBBBB', width, height, 8, 2 if colour else 0, 0, 0, 0)
    return b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')


def meshes_and_images():
    sets = {
        'mesh_stl': {'ascii.stl': stl_ascii(), 'binary.stl': stl_binary()},
        'mesh_ply': {'ascii.ply': ply_ascii(), 'scalar.ply': ply_ascii('deviation'), 'binary.ply': ply_binary()},
        'mesh_obj': {'tet.obj': obj()},
        'mesh_off': {'tet.off': off()},
        'mesh_gz': {'ascii.stl.gz': gzip.compress(stl_ascii(), mtime=0), 'binary.stl.gz': gzip.compress(stl_binary(), mtime=0)},
        'mesh_gltf': {'tet.gltf': gltf()},
        'image': {'grey.png': png(8, 6, False), 'colour.png': png(5, 4, True)},
    }
    for harness, files in sets.items():
        out = os.path.join(HERE, 'corpus', harness)
        for name, data in files.items():
            write(os.path.join(out, name), data)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sb = survey(sys.argv[1])
    seeds_from_base(sb, {'survey.json': 'survey_json', 'nav.csv': 'survey_nav', 'odometry.csv': 'survey_odometry',
                         'dvl.csv': 'survey_dvl', 'features.csv': 'survey_features',
                         'landmarks.csv': 'survey_landmarks', 'truth/poses.csv': 'survey_truth'})
    so = sonar(sys.argv[2])
    seeds_from_base(so, {'sonar.json': 'sonar_json', 'controls.csv': 'sonar_controls',
                         'measurements.csv': 'sonar_measurements'})
    meshes_and_images()
    out = os.path.join(HERE, 'corpus', 'json')
    shutil.rmtree(out, ignore_errors=True)
    for name, path in (('survey.json', 'survey/survey.json'), ('sonar.json', 'sonar/sonar.json'),
                       ('model_pose.json', 'survey/truth/model_pose.json')):
        write(os.path.join(out, name), open(os.path.join(HERE, 'base', path), 'rb').read())


if __name__ == '__main__':
    main()
