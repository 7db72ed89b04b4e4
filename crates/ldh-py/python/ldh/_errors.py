"""The ldh exception family.

Every error raised by ldh is an ``LdhError``; each also derives from the built-in exception a
Python user would catch (``ValueError`` for bad data or arguments, ``TypeError`` for an
argument of the wrong kind, ``FileNotFoundError`` and ``OSError`` for files), so
``except ValueError`` keeps working.
"""


class LdhError(Exception):
    """Base class of all ldh errors."""


class LdhDataError(LdhError, ValueError):
    """The data cannot be used (format, values, timing, too short...)."""


class LdhParamError(LdhError, ValueError):
    """A parameter is outside its valid range."""


class LdhTypeError(LdhError, TypeError):
    """An argument of the wrong kind: a DataFrame or an array given to a function that reads
    files (the message names the function that takes it)."""


class LdhFileNotFoundError(LdhError, FileNotFoundError):
    """A file does not exist."""


class LdhOSError(LdhError, OSError):
    """Any other operating-system error while reading or writing."""


class LdhWarning(UserWarning):
    """A problem in the input that did not stop ldh (a gap, a constant or frozen channel, too
    much timestamp jitter...); the same text is in the report's ``warnings``."""
