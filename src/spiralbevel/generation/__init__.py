"""Equation of meshing of generation -> generated tooth surfaces (face milling)."""

from spiralbevel.generation.flank import ToothFlank, generate_flank
from spiralbevel.generation.meshing import meshing_residual
from spiralbevel.generation.results import FlankPoints, MeanPoint

__all__ = ["ToothFlank", "generate_flank", "FlankPoints", "MeanPoint", "meshing_residual"]
