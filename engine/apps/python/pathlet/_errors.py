"""Exceptions raised by pathlet (the C++ side raises these classes)."""


class GraphError(ValueError):
    """A graph file or an override is wrong. ``diagnostics`` lists every problem as a dict with
    ``file``, ``pointer`` (JSON pointer, e.g. ``/variables``), ``message`` (with a did-you-mean
    where one fits) and ``text`` (``file:pointer: message``, as the command line prints it)."""

    def __init__(self, text, diagnostics=()):
        super().__init__(text)
        self.diagnostics = list(diagnostics)

    @property
    def pointer(self):
        """JSON pointer of the first problem."""
        return self.diagnostics[0]["pointer"] if self.diagnostics else ""


class DataError(ValueError):
    """A data file (pathlines, wall mesh) is wrong; the message names the file and the place."""


class PassError(RuntimeError):
    """A pass failed while running; the message names the pass."""


class GlError(RuntimeError):
    """No OpenGL 4.5 context could be made (the message says what was tried)."""


class ClosedError(RuntimeError):
    """pathlet.close() was called: the process's GL context is gone."""
