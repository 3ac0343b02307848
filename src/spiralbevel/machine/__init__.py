"""Head cutters, machine settings and kinematic chains of face-milling generators (cradle and universal)."""

from spiralbevel.machine.cutter import Blade, HeadCutter
from spiralbevel.machine.seed001 import seed001_blank, seed001_settings
from spiralbevel.machine.settings import MachineSettings
from spiralbevel.machine.universal import UniversalGenerator, UniversalPoints, UniversalSettings

__all__ = ["Blade", "HeadCutter", "MachineSettings", "UniversalGenerator", "UniversalPoints",
           "UniversalSettings", "seed001_blank", "seed001_settings"]
