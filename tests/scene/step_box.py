"""A STEP (ISO 10303-21, AP214) box written from scratch, in a chosen length unit, for import tests.

The box is a manifold solid B-rep: 8 vertices, 12 line edges, 6 planar faces, with its corner at
the origin and the given extents along x, y and z in the file's unit.
"""

from __future__ import annotations

#: the unit entities of each unit name (the SI ones with their prefix; the inch by conversion)
_UNITS = {
    "mm": "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )",
    "cm": "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.CENTI.,.METRE.) )",
    "m": "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )",
}


def step_box(extents: tuple[float, float, float], unit: str) -> str:
    """STEP text of an axis-aligned box ``extents`` (file units) with its corner at the origin."""
    lines: list[str] = []

    def add(text: str) -> int:
        lines.append(text)
        return len(lines)

    if unit == "in":
        mm = add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )")
        dim = add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)")
        measure = add(f"LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#{mm})")
        length = add(f"( CONVERSION_BASED_UNIT('INCH',#{measure}) LENGTH_UNIT() NAMED_UNIT(#{dim}) )")
    else:
        length = add(_UNITS[unit])
    angle = add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )")
    solid = add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )")
    unc = add(f"UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{length},'distance_accuracy_value','')")
    ctx = add(f"( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) "
              f"GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('ctx','3D') )")
    ex, ey, ez = extents
    corners = [(x, y, z) for z in (0.0, ez) for y in (0.0, ey) for x in (0.0, ex)]
    pts = [add(f"CARTESIAN_POINT('',({x:.6f},{y:.6f},{z:.6f}))") for x, y, z in corners]
    verts = [add(f"VERTEX_POINT('',#{p})") for p in pts]
    edges: dict[tuple[int, int], int] = {}

    def edge(a: int, b: int) -> tuple[int, bool]:
        key = (min(a, b), max(a, b))
        if key not in edges:
            pa, pb = corners[key[0]], corners[key[1]]
            d = tuple(q - p for p, q in zip(pa, pb))
            n = max(abs(c) for c in d)
            direction = add(f"DIRECTION('',({d[0] / n:.1f},{d[1] / n:.1f},{d[2] / n:.1f}))")
            vec = add(f"VECTOR('',#{direction},1.)")
            line = add(f"LINE('',#{pts[key[0]]},#{vec})")
            edges[key] = add(f"EDGE_CURVE('',#{verts[key[0]]},#{verts[key[1]]},#{line},.T.)")
        return edges[key], (a, b) == key

    # faces as corner index loops, counter-clockwise seen from outside, with outward normals
    faces = [((0, 2, 3, 1), (0, 0, -1)), ((4, 5, 7, 6), (0, 0, 1)), ((0, 1, 5, 4), (0, -1, 0)),
             ((2, 6, 7, 3), (0, 1, 0)), ((0, 4, 6, 2), (-1, 0, 0)), ((1, 3, 7, 5), (1, 0, 0))]
    face_ids = []
    for loop, normal in faces:
        oriented = []
        for k in range(4):
            e, forward = edge(loop[k], loop[(k + 1) % 4])
            oriented.append(add(f"ORIENTED_EDGE('',*,*,#{e},{'.T.' if forward else '.F.'})"))
        eloop = add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oriented) + "))")
        bound = add(f"FACE_OUTER_BOUND('',#{eloop},.T.)")
        axis = add(f"DIRECTION('',({normal[0]:.1f},{normal[1]:.1f},{normal[2]:.1f}))")
        ref = add("DIRECTION('',(1.,0.,0.))" if normal[0] == 0 else "DIRECTION('',(0.,1.,0.))")
        place = add(f"AXIS2_PLACEMENT_3D('',#{pts[loop[0]]},#{axis},#{ref})")
        plane = add(f"PLANE('',#{place})")
        face_ids.append(add(f"ADVANCED_FACE('',(#{bound}),#{plane},.T.)"))
    shell = add("CLOSED_SHELL('',(" + ",".join(f"#{f}" for f in face_ids) + "))")
    brep = add(f"MANIFOLD_SOLID_BREP('box',#{shell})")
    origin = add("CARTESIAN_POINT('',(0.,0.,0.))")
    zdir, xdir = add("DIRECTION('',(0.,0.,1.))"), add("DIRECTION('',(1.,0.,0.))")
    world = add(f"AXIS2_PLACEMENT_3D('',#{origin},#{zdir},#{xdir})")
    rep = add(f"ADVANCED_BREP_SHAPE_REPRESENTATION('',(#{world},#{brep}),#{ctx})")
    app = add("APPLICATION_CONTEXT('automotive design')")
    add(f"APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})")
    pctx = add(f"PRODUCT_CONTEXT('',#{app},'mechanical')")
    product = add(f"PRODUCT('box','box','',(#{pctx}))")
    formation = add(f"PRODUCT_DEFINITION_FORMATION('','',#{product})")
    dctx = add(f"PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')")
    pdef = add(f"PRODUCT_DEFINITION('design','',#{formation},#{dctx})")
    shape = add(f"PRODUCT_DEFINITION_SHAPE('','',#{pdef})")
    add(f"SHAPE_DEFINITION_REPRESENTATION(#{shape},#{rep})")
    body = "\n".join(f"#{k}={text};" for k, text in enumerate(lines, start=1))
    return ("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('box'),'2;1');\n"
            "FILE_NAME('box.step','2026-01-01T00:00:00',(''),(''),'jackpy tests','','');\n"
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
            f"{body}\nENDSEC;\nEND-ISO-10303-21;\n")
