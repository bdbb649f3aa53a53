"""The schema of a drive's parts with dynamics of their own (values in SI): a permanent-magnet DC machine
(Modelica's DC_PermanentMagnet), its armature supplied with a voltage given as a signal of time, and a speed
controller (Modelica's LimPID) driving a shaft with a torque.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BeforeValidator, Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .schema_motion_source import start_driven_angles
from .schema_speed_reference import speed_reference
from .signals import TimeSignal, signal
from .units import Dimension, Text

SPEED_GAIN = Dimension("torque per speed", "N*m*s/rad", "'100 N*m*s/rad'", radians=-1)  # a controller's gain
VOLTAGE = Dimension("voltage", "V", "'400 V'")
CURRENT = Dimension("current", "A", "'100 A'")
RESISTANCE = Dimension("resistance", "ohm", "'0.05 ohm'")
INDUCTANCE = Dimension("inductance", "H", "'1.5 mH'")
# a DC machine's flux constant: volts per rad/s of its speed, newton metres per ampere of its current
FLUX = Dimension("flux constant", "V*s", "'0.6366 V*s'")

DRIVE_PARTS = ("dc_machines", "induction_machines", "speed_controllers", "motion_sources")  # the drivetrain's keys


class NominalPointSpec(Section):
    """A DC machine's nameplate: its armature voltage, current and speed at the nominal point, where the
    induced voltage, voltage less the resistance's drop, is the flux constant times the speed."""

    voltage: u.quantity(VOLTAGE, gt=0.0) = Field(description="the armature voltage at the nominal point")
    current: u.quantity(CURRENT, gt=0.0) = Field(description="the armature current at the nominal point")
    speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) = Field(description="the speed at the nominal point")


class DcMachineSpec(Section):
    """A permanent-magnet DC machine on a shaft (Modelica's DC_PermanentMagnet without its losses beyond the
    armature's resistance): its armature circuit L di/dt = v - R i - k w, its air-gap torque k i on the shaft, v
    the armature voltage (a signal of time), w the shaft's speed and k the flux constant, given or from the
    nameplate (``nominal``: k = (V_n - R I_n) / w_n).  Its outputs: ``<name>_current`` (A), ``<name>_voltage`` (V),
    ``<name>_torque`` (N*m, the air gap's on its shaft), ``<name>_power`` (W, electrical, in); its summary
    ``<name>_peak_current`` (A)."""

    alternatives = (("flux_constant", "nominal"),)
    shaft: Text = Field(description="the shaft its rotor turns with")
    armature_resistance: u.quantity(RESISTANCE, ge=0.0) = Field(description="R, the armature's resistance")
    armature_inductance: u.quantity(INDUCTANCE, gt=0.0) = Field(description="L, the armature's inductance")
    flux_constant: u.quantity(FLUX, gt=0.0) | None = Field(None, description="k: the induced voltage per rad/s, "
                                                             "the torque per ampere")
    nominal: NominalPointSpec | None = Field(None, description="the nameplate the flux constant is found from")
    rotor_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the rotor's, on its shaft")
    voltage: signal(VOLTAGE) = Field(description="v, the armature voltage: a signal of time")
    current: u.quantity(CURRENT) = Field(0.0, description="the armature current at the start")
    name: str = Field("", exclude=True)  # its key in drivetrain.dc_machines (set there, never written)

    @model_validator(mode="after")
    def _flux_given_once(self):
        if (self.flux_constant is None) == (self.nominal is None):
            raise ScenarioError(".flux_constant", "give either flux_constant (V*s) or nominal (voltage, current "
                                "and speed at the nameplate's point), one of the two")
        if self.nominal is not None and self.nominal.voltage <= self.armature_resistance * self.nominal.current:
            raise ScenarioError(".nominal.voltage", f"{self.nominal.voltage:g} V is no more than the armature "
                                f"resistance's drop at the nominal current, {self.armature_resistance:g} ohm x "
                                f"{self.nominal.current:g} A: the machine would induce no voltage")
        return self

    def flux(self) -> float:
        """k, V*s: given, or the nameplate's induced voltage over its speed."""
        if self.flux_constant is not None:
            return self.flux_constant
        point = self.nominal
        return (point.voltage - self.armature_resistance * point.current) / point.speed


class SupplySpec(Section):
    """An induction machine's three-phase supply: its line voltage (RMS) and frequency, each a signal of time (a
    voltage/frequency inverter ramps both; the mains holds them), switched on at ``on_at``, phase 1's voltage
    sqrt(2) V sin(phase + the angle its frequency has turned since t = 0).  The windings connected in star (each
    sees V / sqrt(3)), in delta (each sees V, 30 degrees ahead), or in star then delta (``delta_at``): a
    star-delta starter."""

    voltage: signal(VOLTAGE) = Field(description="V, the line-to-line voltage (RMS)")
    frequency: signal(u.FREQUENCY) = Field(description="f, its frequency")
    connection: Literal["star", "delta", "star_delta"] = Field("delta", description="how the windings are "
                                                             "connected to it")
    delta_at: u.quantity(u.TIME, gt=0.0) | None = Field(None, description="star_delta: when it switches from star "
                                                        "to delta")
    on_at: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="when it is switched on (before: no voltage, no "
                                              "current)")
    phase: u.quantity(u.ANGLE) = Field(0.0, description="phase 1's voltage's phase at t = 0")

    @model_validator(mode="after")
    def _delta_at_with_star_delta(self):
        if (self.connection == "star_delta") != (self.delta_at is not None):
            raise ScenarioError(".delta_at", "a star-delta starter (connection: star_delta) switches at delta_at; "
                                "give delta_at with it, and only with it")
        if self.delta_at is not None and self.delta_at <= self.on_at:
            raise ScenarioError(".delta_at", f"{self.delta_at:g} s is not after the supply is switched on "
                                f"(on_at {self.on_at:g} s)")
        return self


class InductionMachineSpec(Section):
    """A squirrel-cage induction machine on a shaft (Modelica's IM_SquirrelCage, three phases, its space-phasor
    model in the stator's frame, no losses beyond its resistances): the stator's and the rotor's flux linkages
    are its states, psi_s' = v_s - R_s i_s and psi_r' = -R_r i_r + j p w psi_r, psi_s = (L_ss + L_m) i_s +
    L_m i_r, psi_r = L_m i_s + (L_rs + L_m) i_r, its air-gap torque 3/2 p Im(conj(psi_s) i_s).  Its outputs:
    ``<name>_current`` (A, the stator current's space-phasor magnitude: a phase current's amplitude),
    ``<name>_torque`` (N*m, the air gap's on its shaft), ``<name>_power`` (W, electrical, in),
    ``<name>_voltage`` (V, the winding voltage's space-phasor magnitude)."""

    shaft: Text = Field(description="the shaft its rotor turns with")
    pole_pairs: u.whole("pole pairs") = Field(2, description="p")
    stator_resistance: u.quantity(RESISTANCE, ge=0.0) = Field(description="R_s, a phase's")
    stator_leakage: u.quantity(INDUCTANCE, ge=0.0) = Field(description="L_ss, a phase's stray inductance")
    main_inductance: u.quantity(INDUCTANCE, gt=0.0) = Field(description="L_m, the main field's, a phase's")
    rotor_leakage: u.quantity(INDUCTANCE, ge=0.0) = Field(description="L_rs, the rotor's stray inductance (its "
                                                          "equivalent three-phase winding's)")
    rotor_resistance: u.quantity(RESISTANCE, gt=0.0) = Field(description="R_r, the rotor's (the same winding's)")
    rotor_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the rotor's, on its shaft")
    supply: SupplySpec = Field(description="the three-phase supply its stator is connected to")
    name: str = Field("", exclude=True)  # its key in drivetrain.induction_machines (set there, never written)

    @model_validator(mode="after")
    def _physical(self):
        for key in ("stator_leakage", "rotor_leakage"):
            if getattr(self, key) >= self.main_inductance:
                raise ScenarioError(f".{key}", f"{getattr(self, key):g} H is not less than the main field's "
                                    f"inductance ({self.main_inductance:g} H): no machine leaks more than its main "
                                    "field carries")
        return self


class BrakeSequenceSpec(Section):
    """A hoist drive's brake sequence: the brake released once the drive's torque is proven (its magnitude at
    ``prove_torque``) and the brake's opening time has passed; after the stop command, closed once the speed
    it controls is below ``close_speed`` and the brake's closing time has passed; on an emergency stop (the
    controller's ``emergency_stop_at``, or its overspeed trip ``emergency_stop_above``) the drive's torque taken
    away at once and the brake closed after its closing time."""

    brake: Text = Field(description="the friction brake it works (drivetrain.brakes, operated_by this controller)")
    prove_torque: u.quantity(u.TORQUE, ge=0.0) = Field(description="the torque the drive proves before the brake "
                                                       "is released (its magnitude)")
    release_delay: u.quantity(u.TIME, ge=0.0) = Field(description="the brake's opening time, from the proof")
    stop_at: u.quantity(u.TIME, gt=0.0) | None = Field(None, description="the stop command: from then the brake "
                                                       "closes once the speed is below close_speed")
    close_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) = Field(0.1, description="below this (its magnitude) after "
                                                             "the stop command, the brake is commanded closed")
    close_delay: u.quantity(u.TIME, gt=0.0) = Field(description="the brake's closing time, from its command")

    @model_validator(mode="after")
    def _opens_before_it_closes(self):
        if self.stop_at is not None and self.stop_at <= self.release_delay:
            raise ScenarioError(".stop_at", f"{self.stop_at:g} s is not after the brake can have opened (its "
                                f"release_delay, {self.release_delay:g} s from the proof): the sequence would close "
                                "the brake before it opens")
        return self


class SpeedControllerSpec(Section):
    """A speed controller (Modelica's LimPID, a PI or PID controller): it measures a shaft's speed w against a
    reference r (a signal of time) and drives a shaft with the torque y = limited(k (w_p r - w + I + D)), the
    integral I' = (r - w + (y - v) / (k N_i)) / T_i taking back what the limits cut off of v = k (...) (its
    anti-windup), D the derivative part of w_d r - w filtered with T_d / N_d; the torque on the shaft follows y
    through a first-order lag T_c where one is given (the inverter's current loop).  The limits' corners are
    located as switches are.  Its outputs: ``<name>_reference`` (rad/s), ``<name>_error`` (r - w, rad/s),
    ``<name>_integral`` (I, rad/s: Modelica's I.y), ``<name>_output`` (y, N*m), ``<name>_torque`` (N*m, on the
    shaft: y lagged), and ``<reference_block>_output`` (the reference, named as the block that gives it); its
    summary ``<name>_saturated_time`` (s at a limit)."""

    alternatives = (("output", "integral"),)
    measures: Text = Field(description="the shaft whose speed it controls")
    drives: Text | None = Field(None, description="the shaft its torque drives (default: the one it measures)")
    reference: Annotated[TimeSignal, BeforeValidator(speed_reference), u.ANGULAR_SPEED] = Field(
        description="r, the speed it is asked for: a signal of time, or {kinematic_ptp: {distance, max_speed, "
        "max_acceleration, start}} (Modelica's KinematicPTP integrated), or {s_curve: {speed, acceleration, jerk, "
        "start, hold}} (jerk-limited)")
    reference_block: Text | None = Field(None, description="the signal block the reference comes from, its "
                                         "output written as <reference_block>_output too (Modelica's "
                                         "integrator.y)")
    gain: u.quantity(SPEED_GAIN, gt=0.0) = Field(description="k, the torque per rad/s of error")
    integral_time: u.quantity(u.TIME, gt=0.0) | None = Field(None, description="T_i (none: no integral part, a P "
                                                             "or PD controller)")
    derivative_time: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="T_d (0: no derivative part)")
    max_torque: u.quantity(u.TORQUE) = Field(description="y_max, the most it drives with")
    min_torque: u.quantity(u.TORQUE) | None = Field(None, description="y_min (default -max_torque)")
    anti_windup: u.quantity(u.DIMENSIONLESS, gt=0.0) = Field(0.9, description="N_i: N_i T_i is the time "
                                                             "constant of the anti-windup")
    derivative_filter: u.quantity(u.DIMENSIONLESS, gt=0.0) = Field(10.0, description="N_d: the higher, the "
                                                                   "more ideal the derivative")
    setpoint_weight: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(1.0, description="w_p, the reference's weight "
                                                                 "in the proportional part")
    derivative_setpoint_weight: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(0.0, description="w_d, in the "
                                                                            "derivative part")
    torque_lag: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="T_c: the torque follows y as a first-order "
                                                   "lag (the inverter's current loop; 0: at once)")
    output: u.quantity(u.TORQUE) | None = Field(None, description="y at the start, the integral set to give it "
                                                "(Modelica's steady state: the torque that holds the machine)")
    integral: u.quantity(u.ANGULAR_SPEED) = Field(0.0, description="I at the start (Modelica's xi_start)")
    brake_sequence: BrakeSequenceSpec | None = Field(None, description="the brake it releases and applies: a "
                                                     "hoist drive's sequence")
    emergency_stop_at: u.quantity(u.TIME, gt=0.0) | None = Field(None, description="the drive switched off at "
                                                                 "this time, its brake closing (brake_sequence)")
    emergency_stop_above: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = Field(
        None, description="the drive switched off where the speed it measures first exceeds this (either way: an "
        "overspeed trip), its brake closing (brake_sequence)")
    name: str = Field("", exclude=True)  # its key in drivetrain.speed_controllers (set there, never written)

    @model_validator(mode="after")
    def _limits_and_start(self):
        if self.lowest_torque() >= self.max_torque:
            raise ScenarioError(".min_torque" if self.min_torque is not None else ".max_torque",
                                f"the limits must leave room: y_min {self.lowest_torque():g} N*m is not below y_max "
                                f"{self.max_torque:g} N*m")
        if self.output is not None and "integral" in self.model_fields_set:
            raise ScenarioError(".output", "give either output (y at the start) or integral (I at the start), "
                                "not both")
        if self.output is not None and not self.lowest_torque() <= self.output <= self.max_torque:
            raise ScenarioError(".output", f"{self.output:g} N*m is outside the limits [{self.lowest_torque():g}, "
                                f"{self.max_torque:g}] N*m")
        for key in ("emergency_stop_at", "emergency_stop_above"):
            if getattr(self, key) is not None and self.brake_sequence is None:
                raise ScenarioError(f".{key}", "an emergency stop closes the drive's brake: give the "
                                    "brake_sequence that works it")
        if self.emergency_stop_at is not None and self.emergency_stop_at <= self.brake_sequence.release_delay:
            raise ScenarioError(".emergency_stop_at", f"{self.emergency_stop_at:g} s is not after the brake can "
                                f"have opened (release_delay {self.brake_sequence.release_delay:g} s from the proof)")
        if self.output is not None and self.integral_time is None:
            raise ScenarioError(".output", "a controller without an integral part (no integral_time) has no state "
                                "to start at an output")
        return self

    def lowest_torque(self) -> float:
        return -self.max_torque if self.min_torque is None else self.min_torque

    def lowered(self, scenario) -> "SpeedControllerSpec":
        """With its measured shaft's speed at the start written in (rad/s), and the reference's there."""
        shaft = scenario.drivetrain.shafts[self.measures]
        if getattr(self.reference, "integrated", False):  # an S-curve: a profile from rest
            return self.with_resolved(start_speed=shaft.train(scenario)[2], start_reference=0.0,
                                      rope_per_radian=self._rope_per_radian(scenario))
        return self.with_resolved(start_speed=shaft.train(scenario)[2], start_reference=self.reference.value_at(0.0),
                                  rope_per_radian=self._rope_per_radian(scenario))

    def _rope_per_radian(self, scenario) -> float | None:
        """m of rope the drum pays out per rad of the shaft it controls, where a load hangs from a shaft geared
        to it (None: no load, or one on a shaft of its own: the rollback and stopping distances are not told)."""
        load = scenario.drivetrain.load
        if load is None or load.path == "level":
            return None
        root, ratio = scenario.drivetrain.shafts[self.measures].train(scenario)[:2]
        load_root, load_ratio = scenario.drivetrain.shafts[load.shaft].train(scenario)[:2]
        return load.rope_radius * load_ratio / ratio if root == load_root else None


def check_drive_parts(drivetrain, names_taken: set, is_name) -> None:
    """Each machine and controller names shafts there are; names are words (``is_name``) not taken by another
    part."""
    for kind in DRIVE_PARTS:
        for name, part in getattr(drivetrain, kind).items():
            if not is_name(name) or name in names_taken:
                raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                    "underscores starting with a letter, not 'ground' and not the name of "
                                    "another part (they name the outputs)")
            names_taken.add(name)
            block = getattr(part, "reference_block", None)
            if block is not None:
                if not is_name(block) or block in names_taken:
                    raise ScenarioError(f"drivetrain.{kind}.{name}.reference_block", "a name is a word of letters, "
                                        "digits and underscores starting with a letter, not 'ground' and not the "
                                        "name of another part (it names an output)")
                names_taken.add(block)
            for key in ("shaft", "measures", "drives"):
                shaft = getattr(part, key, None)
                driven_mass = kind == "motion_sources" and shaft in drivetrain.masses  # a source drives a mass too
                if shaft is not None and shaft not in drivetrain.shafts and not driven_mass:
                    raise ScenarioError(f"drivetrain.{kind}.{name}.{key}", f"there is no shaft {shaft!r} "
                                        f"(shafts: {', '.join(drivetrain.shafts)})")
    _check_brake_sequences(drivetrain)
    start_driven_angles(drivetrain)


def _check_brake_sequences(drivetrain) -> None:
    """Each brake sequence works a brake operated by its controller; each operated brake has its sequence; one
    sequence a drivetrain (its rollback and stopping distances are the scene's)."""
    sequenced = {name: c.brake_sequence for name, c in drivetrain.speed_controllers.items() if c.brake_sequence}
    if len(sequenced) > 1:
        raise ScenarioError(f"drivetrain.speed_controllers.{list(sequenced)[1]}.brake_sequence", "one drive "
                            "sequences a brake: the drivetrain has one brake sequence")
    for name, sequence in sequenced.items():
        brake = drivetrain.brakes.get(sequence.brake)
        if brake is None or brake.operated_by != name:
            raise ScenarioError(f"drivetrain.speed_controllers.{name}.brake_sequence.brake", f"there is no brake "
                                f"{sequence.brake!r} operated_by {name!r} (brakes: {', '.join(drivetrain.brakes)})")
        if sequence.stop_at is not None and drivetrain.speed_controllers[name].emergency_stop_at is not None:
            raise ScenarioError(f"drivetrain.speed_controllers.{name}.emergency_stop_at", "a run ends with a stop "
                                "or an emergency stop: give stop_at or emergency_stop_at, not both")
    for name, brake in drivetrain.brakes.items():
        if brake.operated_by is not None and brake.operated_by not in sequenced:
            raise ScenarioError(f"drivetrain.brakes.{name}.operated_by", f"there is no speed controller "
                                f"{brake.operated_by!r} with a brake_sequence working it")
