import os
import sys

# shared test data of several folders (tests/_hypoid_sample2.py) importable under --import-mode=importlib
sys.path.insert(0, os.path.dirname(__file__))

# small dense solves are far slower with threaded BLAS on 2 cores (LTCA); set before numpy is imported
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
# the FE compliance cache of LTCA goes to a fresh directory per test session
os.environ.setdefault("SPIRALBEVEL_CACHE", __import__("tempfile").mkdtemp(prefix="spiralbevel-cache-"))
# a kernel called from the package with argument types missing from the ahead-of-time extension's table fails the test
# that made the call (tests/_core/test_aot.py; _core/jit.py)
os.environ.setdefault("SPIRALBEVEL_AOT_STRICT", "1")

import matplotlib

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")
