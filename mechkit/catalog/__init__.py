"""The catalog of registered mechanisms: parameters, their ranges, the contract, the registry.

`params` (`MechanismParams`, `param`), `ranges` (each parameter's accepted range), `contract`
(`MechanismSpec`: everything mechkit reads about a registered mechanism), `registry` (the explicit,
lazy table of the mechanisms that ship with mechkit).
"""
