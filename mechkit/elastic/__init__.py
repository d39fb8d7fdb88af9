"""Elastic mechanisms: the reactions rigid statics leaves open, stiffness, deflection and natural
frequencies, from the mechanism's own elasticity (beam sections per link, joint stiffness).
"""

from mechkit.elastic.description import parse_elastic, with_elastic
from mechkit.elastic.model import BodyStiffness, CompliantReactions, ElasticModel
from mechkit.elastic.modes import Modes
from mechkit.elastic.sections import ElasticData, JointElasticity, Section

__all__ = ["BodyStiffness", "CompliantReactions", "ElasticData", "ElasticModel", "JointElasticity", "Modes", "Section",
           "parse_elastic", "with_elastic"]
