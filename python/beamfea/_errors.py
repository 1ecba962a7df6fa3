"""beamfea's exceptions (raised by the compiled engine, defined here so that they are plain
Python classes that users can catch, pickle and subclass)."""
from typing import Optional


class Error(Exception):
    """Base of beamfea's errors."""


class InputError(Error, ValueError):
    """Bad input: malformed JSON, an unknown key, a missing or invalid field.

    Attributes:
        pointer: the RFC 6901 JSON pointer of the field at fault ("/elements/3/section"),
            or None when the error is not about one field (a file that cannot be read).
        entity: the thing the pointer lies in ("element 'e3'", "analysis 'K'"), or None.
    """

    def __init__(self, message: str, pointer: Optional[str] = None, entity: Optional[str] = None):
        super().__init__(message)
        self.pointer = pointer
        self.entity = entity

    def __reduce__(self):
        return (type(self), (str(self), self.pointer, self.entity))


class ModelError(Error):
    """A model that cannot be analysed as given (an element of zero length, two joints on one
    DOF...). `entity` names the node, element, joint or DOF at fault."""

    def __init__(self, message: str, entity: Optional[str] = None):
        super().__init__(message)
        self.entity = entity

    def __reduce__(self):
        return (type(self), (str(self), self.entity))


class BeamfeaWarning(UserWarning):
    """A warning of the engine: something in the model or the answer that is probably not what
    was meant (a material never used, a load on a fully supported node, a path that used up
    max_steps, an ill-conditioned stiffness, statically indeterminate constraint rows). The run
    goes on; results.json lists the same lines in "warnings"."""
