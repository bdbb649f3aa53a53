"""The error every bad scenario raises."""

from __future__ import annotations


class ScenarioError(ValueError):
    """A bad scenario: names the key, and the file and line where known."""

    def __init__(self, key: str, message: str, *, source: str | None = None, line: int | None = None,
                 also: tuple[ScenarioError, ...] = ()):
        self.key = key
        self.message = message
        self.source = source
        self.line = line
        self.also = also  # the others found with it (--strict says every value at once), each its own line
        super().__init__(self.__str__())

    def each(self) -> tuple[ScenarioError, ...]:
        """This error and those found with it, in the order found."""
        return (self, *self.also)

    def __str__(self) -> str:
        where = ""
        if self.source:
            where = f"{self.source}:{self.line}: " if self.line else f"{self.source}: "
        key = f"{self.key}: " if self.key else ""
        return " ".join(f"{where}{key}{self.message}".splitlines())  # always one line
