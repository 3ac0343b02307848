import os
import sys

# make the shared helpers of this folder importable under --import-mode=importlib
sys.path.insert(0, os.path.dirname(__file__))
