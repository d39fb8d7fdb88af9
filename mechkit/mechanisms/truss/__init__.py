"""The tetrahedral truss of Xu et al. 2017 (references/003): what the unit `tetra_3rr3uru` and the
composite `deployable_9rr12uru` share.

Modules, lowest first: `geometry` (the paper's eq. 6-13, numpy only), `drives` (the drive laws of
section 3.2), `params` (`TetraParams`, the unit's parameters, which the composite extends),
`joint_state` (the drive laws on the web-rod joints), `fold` (the 200 s fold on a model: continuation
of the closure; the "fold" scene), `nodes` (node centres read from a model), `checks` (deviations
along the fold, rows of `mechkit report`). No mechanism is declared here.
"""
