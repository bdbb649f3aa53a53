"""What an electrical machine's element shares (a DC machine's, an induction machine's): the electrical energy
it takes in and its copper losses as states, the magnetic energy it stores, in the energy ledger."""

from __future__ import annotations

from ..core.element import AbstractElement


class AbstractElectricalMachine(AbstractElement):
    """The ledger of a machine named ``section``: ``<name>_electrical_energy`` (work: what its supply gives),
    ``<name>_copper_loss`` (loss: its resistances' heat), both states, and ``<name>_magnetic_energy`` (potential:
    what its inductances hold)."""

    @property
    def input_state(self) -> str:
        return f"{self.section}_electrical_energy"

    @property
    def copper_state(self) -> str:
        return f"{self.section}_copper_loss"

    @property
    def magnetic_term(self) -> str:
        return f"{self.section}_magnetic_energy"

    @property
    def ledger_kinds(self) -> dict:
        return {self.input_state: "work", self.copper_state: "loss", self.magnetic_term: "potential"}

    def electrical_ledger(self, x, magnetic) -> dict:
        """The ledger's terms, ``magnetic`` the energy its inductances hold now (J)."""
        return {self.input_state: x.state(self.input_state), self.copper_state: x.state(self.copper_state),
                self.magnetic_term: magnetic}
