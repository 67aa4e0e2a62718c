"""What is thrown and what throws it: parts, the arm, fixtures, and the System they form.

=================  ===============================================================
:mod:`.geometry`   convex polygons: checks, orientation, mass properties, side table
:mod:`.part`       :class:`Part` (vertices, mass, CM, ρ, point masses) and :class:`Side`
:mod:`.catalogue`  canonical parts: the paper's 30-60-90 triangle, rectangles, regular polygons
:mod:`.arm`        :class:`Arm` (h, g, length, μ) and the paper's regime
:mod:`.fixtures`   :class:`Wall`, :class:`Cavity` as arm-frame geometry
:mod:`.system`     :class:`System`: arm + fixtures + rest angle α, what models take
=================  ===============================================================
"""
