"""A second opinion for any mechanism: efforts and joint reactions by sequential single-open-chain
(SOC) virtual work, with the ordered sub-kinematic chains (SKCs) found automatically.

Modules, each importing only those before it: `structure_graph` (the structure graph), `instant`
(one instant from Pinocchio kinematics), `decomposition` (Dulmage-Mendelsohn block-triangular form read as
SKCs), `solve` (per-SKC virtual work with `mechkit.validation.soc`), `opinion` (`SecondOpinion`:
decompose once, solve any instant), `agreement` (agreement with constrained RNEA over a
scene).
"""
