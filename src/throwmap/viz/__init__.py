"""Figures and animations (matplotlib, imported on first use; importing these modules does not load it).

Every figure draws a result the library has already computed — nothing here
throws a part or iterates a map — takes an optional ``ax``/``axes`` and returns
the matplotlib Figure. The result objects' ``.plot()`` methods delegate here.
Every figure's title names the part, h, ω and the model (:func:`.style.describe_setting`).

=================  ===============================================================
:mod:`.style`      pyplot on first use, side/attractor colours, units, saving
:mod:`.throw_map`  T(x) against x per side (paper Fig. 2 and its analogue)
:mod:`.orbit`      x against throw number (paper Figs. 7, 16)
:mod:`.limit_set`  the limit set along the arm (paper Fig. 5 analogue)
:mod:`.basins`     basin map: attractor by colour, throws to reach it by shade
:mod:`.funnels`    funnel graph by priority (paper Sec. I-A)
:mod:`.comparison` jog error of approximate models against a reference
:mod:`.frames`     one animation frame: scene, scale bar, phase labels
:mod:`.animation`  GIF/MP4 of a recorded trajectory, and stills
=================  ===============================================================
"""
