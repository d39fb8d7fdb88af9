"""The numerical core: a Pinocchio model with loop closures, its kinematics and constrained dynamics."""
