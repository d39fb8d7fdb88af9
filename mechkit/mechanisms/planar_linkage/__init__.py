"""Shared by the planar calibration linkages four_bar and five_bar: their bench methods and references.

Modules (each imports only the core, `mechkit.validation` and the siblings listed before it):
`state` (a linkage's closed-form motion at a bench sample, joint vectors), `lagrange` (the linkage
in Lagrange's equations of the first kind), `methods` (the `BenchMethod`s and `BenchReference`s a
linkage declares on its `SPEC`).
"""
