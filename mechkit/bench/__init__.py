"""Speed and accuracy of every method, per mechanism and quantity (`mechkit bench`).

For each mechanism the bench draws a few assembled states near the home pose (inputs offset by up
to `sampling.INPUT_SPREAD`, random input rates and accelerations), or along the mechanism's own
motion where its spec declares one (`MechanismSpec.bench_states`), computes the best reference
available for each quantity, then runs every method on those states: first once for its error,
then in a timed loop (one process, garbage collector off) for microseconds per call (median and
inter-quartile range over repeats).

Quantities (`mechkit.catalog.contract.BENCH_QUANTITIES`) and their errors (`errors`): "assembly" (q from the
input coordinates), "inverse_kinematics" (the actuated inputs from the rest of q: only the
mechanisms' own closed forms), "forward_dynamics" (accelerations under the reference efforts),
"inverse_dynamics" (efforts and joint reactions for (q, v, a)).

Methods and references (`methods`): the core's methods with their accuracy knobs swept, the
mechanism's own methods and references as its spec declares them (`MechanismSpec.bench_methods`,
`MechanismSpec.bench_references`), and the peer simulators MuJoCo and Drake (`peers`). A method or
reference is a callable `fn(mechanism, sample)` of a `mechkit.mechanism.Mechanism` and a
`sampling.Sample` (fields `inputs`, `rates`, `accelerations` in the order of `input_names`; `q`,
`v`, `a`, `tau` joint vectors; `extra`, a dict for cached data, with "t" and "previous" for states
along the mechanism's own motion) returning q (nq,) for assembly, the actuated inputs (na,) for
inverse kinematics, a (nv,) for forward dynamics, or for inverse dynamics any object or dict with `efforts`
({actuated joint: N m or N}) and optionally `reactions` ({joint: (6,) world wrench [f, m] parent
on child at the joint origin, or a `JointReaction`}). A callable may raise a `MechkitError`: the
table then shows it as the outcome.

Modules, each one concept, each importing only modules listed before it: `sampling`, `errors`, `methods`, `peers`,
`results`, `timing` (time per call, a method's row, the ratio columns), `scale` (cost vs model
size), `loadtime` (first load in a fresh process), `charts`, `failure_atlas` (where each method
fails: its own studies and those the mechanisms declare), `markdown` (tables, goals,
docs/benchmarks.md), `run` (`bench_mechanism`, `run`); beside them, the rows of `bench --speed`
(`dynamics_speed`, `ladder`, `motion_speed`, `load_speed`, `second_opinion_speed`, `sweep_speed`), `field` (the
field's robots of docs/field_robots.md and their load times, a section `tools/bench_all.py --speed` adds) and
`core_cost` (the core's calls against the raw Pinocchio calls, `tools/bench_core.py`). Nothing here
prints: `mechkit.cli` and the tools print the tables and write the files.
"""

from mechkit.bench.timing import time_per_call

__all__ = ["time_per_call"]
