"""``python -m tensegrity.envs MODEL``: prints the scene TOML of a robot of
:mod:`tensegrity.envs.models` (``superball``, ``toroid_wheel``) with its defaults."""

import sys

from . import models

MODELS = {"superball": models.superball, "toroid_wheel": models.toroid_wheel}

if len(sys.argv) != 2 or sys.argv[1] not in MODELS:
    sys.exit(f"usage: python -m tensegrity.envs {{{','.join(MODELS)}}}")
print(f"# tensegrity.envs.models.{sys.argv[1]}() (python -m tensegrity.envs {sys.argv[1]}): "
      "see that function's documentation")
print(MODELS[sys.argv[1]]().to_toml())
