"""tests/dem/ on the import path, so that a test may use the scene helpers of another folder's
test, named through its folder: ``from control.test_controllers import walled_cloud`` (each folder
is a namespace package; a module of the same name elsewhere on the path takes precedence)."""
import sys
from pathlib import Path

sys.path.append(str(Path(__file__).parent))
