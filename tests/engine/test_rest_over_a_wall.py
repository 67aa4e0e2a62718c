"""A part at rest on the arm whose upper vertex overhangs past an end wall's top is on the arm (``ok``).

The engine read a walled rest's reach off every vertex; a flat rest with both support vertices inside L and
another vertex above the wall's top, past L, was called ``off_end`` — for a part that never moved (ω = 0), where
``throw()`` accepts the start and rigid_body rests it. The reach is now read off the vertices on the surface.
"""

import throwmap as tm

POLY = [(0.06926097540717016, 0.0), (0.12464620819076089, 0.11100744363459013),
        (0.09911896793515969, 0.1385237968820669), (0.0, 0.09133816736568674),
        (0.018068938412687953, 0.008758747059442643)]


def test_a_rest_overhanging_the_wall_top_is_ok_for_the_engine_as_for_rigid_body():
    part = tm.Part.from_vertices(POLY, mass=0.040393221271804794)
    arm = tm.Arm(h=-0.027967841608095276, mu=1, length=0.4839468642037319)
    wall = (tm.Wall(0.03),)
    for x in (0.4237, 0.432):  # side 3's outer support vertex 16 and 7.6 mm inside L; vertex 1 past L, above the top
        e = tm.throw(part, arm, x, 3, 0.0, "engine", fixtures=wall)
        r = tm.throw(part, arm, x, 3, 0.0, "rigid_body", fixtures=wall)
        assert (e.status, e.side) == (r.status, r.side) == (tm.Status.OK, 3), (e, r)
        assert abs(e.x - x) < 1e-4
