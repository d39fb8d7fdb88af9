"""The base: what every layer may use and that knows nothing of mechanisms.

`exceptions` (the errors mechkit raises), `arguments` (checks of what a public function is given),
`joint_arguments` (checks of arguments that name joints),
`spatial` (small 3D helpers), `atomic` (atomic file writes), `resources` (where the packaged xacro
templates and URDFs are), `plotting` (matplotlib on the Agg backend, for figure files).
"""
