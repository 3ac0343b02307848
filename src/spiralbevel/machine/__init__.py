"""Head cutters, machine settings and kinematic chains of face-milling generators."""

from spiralbevel.machine.cutter import Blade, HeadCutter
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings
from spiralbevel.machine.settings import MachineSettings

__all__ = ["Blade", "HeadCutter", "MachineSettings", "seed001_blank", "seed001_settings"]
