"""Force elements: generalised forces a mechanism's own parts apply (joint springs and dampers).

`JointSprings` (`springs`): the springs and dampers a description declares, as generalised forces of
one state or N.
"""

from mechkit.forces.springs import JointSprings

__all__ = ["JointSprings"]
