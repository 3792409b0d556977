import json, struct, sys
data = open(sys.argv[1], 'rb').read()
magic, ver, length = struct.unpack_from('<4sII', data, 0)
off = 12; js = None; binc = None
while off < len(data):
    clen, ctype = struct.unpack_from('<II', data, off); off += 8
    chunk = data[off:off+clen]; off += clen
    if ctype == 0x4E4F534A: js = json.loads(chunk)
    else: binc = chunk
def mat_mul(a, b):  # column-major 4x4 lists
    r = [0.0]*16
    for c in range(4):
        for rr in range(4):
            r[c*4+rr] = sum(a[k*4+rr]*b[c*4+k] for k in range(4))
    return r
def node_mat(n):
    if 'matrix' in n: return n['matrix']
    t = n.get('translation', [0,0,0]); q = n.get('rotation', [0,0,0,1]); s = n.get('scale', [1,1,1])
    x,y,z,w = q
    R = [1-2*(y*y+z*z), 2*(x*y+z*w), 2*(x*z-y*w), 0,
         2*(x*y-z*w), 1-2*(x*x+z*z), 2*(y*z+x*w), 0,
         2*(x*z+y*w), 2*(y*z-x*w), 1-2*(x*x+y*y), 0,
         0,0,0,1]
    S = [s[0],0,0,0, 0,s[1],0,0, 0,0,s[2],0, 0,0,0,1]
    T = [1,0,0,0, 0,1,0,0, 0,0,1,0, t[0],t[1],t[2],1]
    return mat_mul(T, mat_mul(R, S))
def accessor(i):
    a = js['accessors'][i]; bv = js['bufferViews'][a['bufferView']]
    base = bv.get('byteOffset', 0) + a.get('byteOffset', 0)
    ncomp = {'SCALAR':1,'VEC3':3,'VEC2':2,'VEC4':4}[a['type']]
    fmt = {5126:'f',5125:'I',5123:'H',5121:'B'}[a['componentType']]
    size = struct.calcsize(fmt)
    stride = bv.get('byteStride', size*ncomp)
    return [struct.unpack_from('<'+fmt*ncomp, binc, base + k*stride) for k in range(a['count'])]
tris = []; parts = []
def visit(ni, parent):
    n = js['nodes'][ni]; m = mat_mul(parent, node_mat(n))
    if 'mesh' in n:
        for p in js['meshes'][n['mesh']]['primitives']:
            if p.get('mode', 4) != 4: continue
            pos = accessor(p['attributes']['POSITION'])
            pos = [tuple(m[0]*v[0]+m[4]*v[1]+m[8]*v[2]+m[12] for _ in [0]) + tuple(m[1]*v[0]+m[5]*v[1]+m[9]*v[2]+m[13] for _ in [0]) + tuple(m[2]*v[0]+m[6]*v[1]+m[10]*v[2]+m[14] for _ in [0]) for v in pos]
            idx = [i[0] for i in accessor(p['indices'])] if 'indices' in p else list(range(len(pos)))
            parts.append(len(tris))
            for k in range(0, len(idx)-2, 3):
                tris.append((pos[idx[k]], pos[idx[k+1]], pos[idx[k+2]]))
    for c in n.get('children', []): visit(c, m)
I = [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]
for ni in js['scenes'][js.get('scene', 0)]['nodes']: visit(ni, I)
with open(sys.argv[2], 'wb') as f:
    f.write(b'\0'*80); f.write(struct.pack('<I', len(tris)))
    for t in tris:
        f.write(struct.pack('<3f', 0, 0, 0))
        for v in t: f.write(struct.pack('<3f', *v))
        f.write(b'\0\0')
print(len(tris))
parts.append(len(tris))
with open(sys.argv[2] + '.parts', 'w') as f:
    f.write(' '.join(map(str, parts)))
print(len(parts) - 1, 'parts')
