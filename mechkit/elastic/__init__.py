"""Elastic mechanisms: the reactions rigid statics leaves open, stiffness, deflection and natural
frequencies, from the mechanism's own elasticity (beam sections per link, joint stiffness).
"""

from mechkit.elastic.body_stiffness import BodyStiffness
from mechkit.elastic.elastic_model import CompliantReactions, ElasticModel
from mechkit.elastic.modes import Modes
from mechkit.elastic.sections import ElasticData, JointElasticity, Section
from mechkit.elastic.urdf_elements import parse_elastic, with_elastic

__all__ = [
    "BodyStiffness",
    "CompliantReactions",
    "ElasticData",
    "ElasticModel",
    "JointElasticity",
    "Modes",
    "Section",
    "parse_elastic",
    "with_elastic",
]
