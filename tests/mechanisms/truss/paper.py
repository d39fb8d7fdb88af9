"""The truss unit of the paper's eq. (6)-(13) (web rod 0.590 m, base links 0.2504 m and 0.250 m) and the
instants of its 200 s fold the tests sample (s)."""

from __future__ import annotations

from mechkit.mechanisms.truss.geometry import TrussGeometry

GEOMETRY = TrussGeometry(0.590, 0.2504, 0.250)
TIMES = (0.0, 37.0, 100.0, 163.0, 200.0)
