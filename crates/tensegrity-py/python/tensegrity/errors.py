"""The exceptions of the package.

Every error of the engine has a category; it picks the class raised:

======================  ======================================  ==============================
category                class                                   also an instance of
======================  ======================================  ==============================
bad input               :class:`InputError`                     ``ValueError``
resource (a limit)      :class:`ResourceError`                  ``ComputationError``, ``RuntimeError``
numerical failure       :class:`ComputationError`               ``RuntimeError``
interrupted (Ctrl-C)    :class:`Interrupted`                    ``KeyboardInterrupt``
======================  ======================================  ==============================

The message is the command line's, word for word: a parameter is written as its flag
(``--t-end`` for the keyword ``t_end``; the keyword is the flag in snake_case), e.g.
``invalid value for --sides: sides = 1: must be at least 3``. ``parameter`` holds the keyword a
bad value was given for (``None`` when the error is not about one keyword).
"""


class TensegrityError(Exception):
    """Base of the package's errors (an interruption excepted, see :class:`Interrupted`)."""

    parameter = None
    partial = None


class InputError(TensegrityError, ValueError):
    """Bad input: a keyword value out of range, an invalid structure or scene (the message
    names the item, e.g. ``string 0: stiffness must be positive and finite, got -1``)."""


class ComputationError(TensegrityError, RuntimeError):
    """The computation failed (not prestressable, diverged, a load not carried, …).

    ``partial`` holds the report of a run that stopped early (``roll``), else ``None``."""


class ResourceError(ComputationError):
    """Refused before any work: the estimated memory, work or output is above the limit
    (keywords ``max_memory``, ``max_work``, ``max_output`` of every function)."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) during a computation: the engine stopped and control came back.

    ``partial`` holds the results so far, as the command line keeps them: for ``simulate``
    a dict ``{"t", "trajectory"}`` of the samples before the interruption, for ``roll`` the
    partial run's report, for ``sweep`` the rows written so far (the file of ``out=`` keeps
    them, marked incomplete); ``None`` for a command that cannot stop early."""

    parameter = None
    partial = None
