"""A speed controller driving a shaft of a drawn drivetrain with a torque (Modelica's LimPID)."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import AbstractElement
from . import _brake_sequence as sequence
from ._signal import signal_at, signal_fields, signal_tables


class SpeedController(AbstractElement):
    """Modelica's LimPID on a speed: the error e = r - w of the measured shaft's speed w from the reference r (a
    signal of time), the unlimited output v = k (w_p r - w + I + D) and the torque y = v limited to [y_min,
    y_max] on the shaft it drives.  The integral's state I' = (e + (y - v) / (k N_i)) / T_i (its anti-windup:
    what the limits cut off flows back with the time constant N_i T_i); the derivative part D = N_d (u - z) of
    u = w_d r - w, filtered by the state z' = N_d (u - z) / T_d.  A controller without T_i has no integral, one
    with T_d = 0 no derivative (neither state exists).

    The limiter's two corners (v through y_max or y_min) are located as a switch is, and recorded as the events
    ``<name>_saturate`` (v reaches a limit) and ``<name>_desaturate`` (it comes back within); the time it spends
    at a limit is the summary's ``<name>_saturated_time``.  With a torque lag T_c (the inverter's current loop) the
    torque on the shaft is a state following y, T_c tau' = y - tau, started at y.  The torque's work on the shaft
    it drives is a state and the ledger's work.  With a brake sequence (:mod:`._brake_sequence`) it releases and
    applies its brake and takes its torque away once the brake is applied (through its torque lag, where it has
    one), and an emergency stop takes its torque away at once: at its time (a table's step), or where the speed it
    measures first exceeds its trip speed (an overspeed trip, the crossing located as a switch is).
    """

    gain: object  # k, N*m*s/rad
    integral_time: object  # T_i, s (a placeholder where it has no integral)
    derivative_time: object  # T_d, s
    max_torque: object  # y_max, N*m
    min_torque: object  # y_min, N*m
    anti_windup: object  # N_i
    derivative_filter: object  # N_d
    setpoint_weight: object  # w_p
    derivative_setpoint_weight: object  # w_d
    start_integral: object  # I at t = 0
    start_filter: object  # z at t = 0: the derivative part's input there (it starts at rest)
    torque_lag: object  # T_c, s (a placeholder where it has none)
    start_output: object  # y at t = 0: the lagged torque's start
    reference_times: object  # s
    reference_values: object  # rad/s
    reference_amplitudes: object
    reference_frequencies: object  # Hz
    reference_phases: object  # rad
    reference_envelope_times: object = None
    reference_envelope_values: object = None
    # its brake sequence (placeholders where it has none)
    prove_torque: object = 0.0  # N*m
    release_delay: object = 0.0  # s
    close_delay: object = 0.0  # s
    close_speed: object = 0.0  # rad/s
    rope_per_radian: object = 0.0  # m of rope a rad of the shaft it measures
    emergency_stop_at: object = 0.0  # s
    trip_speed: object = 0.0  # rad/s, the overspeed trip's
    stopping_times: object = None  # s: the stop command, a step of a table of time
    stopping_values: object = None
    emergency_times: object = None  # s: the emergency stop, another
    emergency_values: object = None
    brake: str = static("")  # the brake its sequence works ("": none)
    has_rope: bool = static(False)  # a load hangs from a shaft geared to the one it measures
    has_stop: bool = static(False)  # its sequence has a stop command
    has_scheduled_stop: bool = static(False)  # an emergency stop at a time
    has_trip: bool = static(False)  # an emergency stop where the speed exceeds the trip speed
    measures: str = static("")
    drives: str = static("")
    has_integral: bool = static(True)
    has_derivative: bool = static(False)
    has_lag: bool = static(False)
    integrates_reference: bool = static(False)  # its table is the reference's acceleration (an S-curve)
    reference_block: str = static("")  # the signal block whose output the reference is ("": none named)
    section: str = static("")  # its key in drivetrain.speed_controllers

    @classmethod
    def from_spec(cls, spec) -> "SpeedController":
        speed, reference = spec.resolved("start_speed"), spec.resolved("start_reference")
        filtered = spec.derivative_setpoint_weight * reference - speed  # the derivative part at rest: D = 0
        proportional = spec.setpoint_weight * reference - speed
        integral = spec.integral if spec.output is None else spec.output / spec.gain - proportional
        output = min(max(spec.gain * (proportional + (integral if spec.integral_time is not None else 0.0)),
                         spec.lowest_torque()), spec.max_torque)
        return cls(gain=spec.gain, integral_time=1.0 if spec.integral_time is None else spec.integral_time,
                   derivative_time=spec.derivative_time, max_torque=spec.max_torque,
                   min_torque=spec.lowest_torque(), anti_windup=spec.anti_windup,
                   derivative_filter=spec.derivative_filter, setpoint_weight=spec.setpoint_weight,
                   derivative_setpoint_weight=spec.derivative_setpoint_weight, start_integral=integral,
                   start_filter=filtered, torque_lag=spec.torque_lag if spec.torque_lag > 0.0 else 1.0,
                   start_output=output, **signal_fields(spec.reference, "reference"),
                   integrates_reference=getattr(spec.reference, "integrated", False),
                   reference_block=spec.reference_block or "", measures=spec.measures,
                   drives=spec.drives or spec.measures, has_integral=spec.integral_time is not None,
                   has_derivative=spec.derivative_time > 0.0, has_lag=spec.torque_lag > 0.0, section=spec.name,
                   **cls._sequence_fields(spec))

    @staticmethod
    def _sequence_fields(spec) -> dict:
        brake = spec.brake_sequence
        if brake is None:
            return {}
        rope = spec.resolved("rope_per_radian")
        stopping, emergency = sequence.step_table(brake.stop_at), sequence.step_table(spec.emergency_stop_at)
        return dict(prove_torque=brake.prove_torque, release_delay=brake.release_delay, close_delay=brake.close_delay,
                    close_speed=brake.close_speed, rope_per_radian=0.0 if rope is None else rope,
                    emergency_stop_at=spec.emergency_stop_at or 0.0, trip_speed=spec.emergency_stop_above or 0.0,
                    stopping_times=stopping[0],
                    stopping_values=stopping[1], emergency_times=emergency[0], emergency_values=emergency[1],
                    brake=brake.brake, has_rope=rope is not None, has_stop=brake.stop_at is not None,
                    has_scheduled_stop=spec.emergency_stop_at is not None,
                    has_trip=spec.emergency_stop_above is not None)

    @property
    def has_emergency_stop(self) -> bool:
        """An emergency stop at a time, or an overspeed trip, or both (whichever comes first)."""
        return self.has_scheduled_stop or self.has_trip

    @property
    def integral_state(self) -> str:
        return f"{self.section}_integral"

    @property
    def filter_state(self) -> str:
        return f"{self.section}_derivative_filter"

    @property
    def torque_state(self) -> str:
        return f"{self.section}_torque"

    @property
    def work_state(self) -> str:
        return f"{self.section}_work"

    @property
    def limit_kinds(self) -> tuple:
        return (f"{self.section}_upper_limit", f"{self.section}_lower_limit")

    @property
    def observation_kinds(self) -> tuple:
        return self.limit_kinds + (sequence.guard_kinds(self) if self.brake else ())

    @property
    def crossings(self) -> tuple:
        return self.observation_kinds

    @property
    def crossing_events(self) -> dict:
        events = (f"{self.section}_desaturate", f"{self.section}_saturate")  # rising (back within), falling
        return {kind: events for kind in self.limit_kinds}

    @property
    def summaries(self) -> dict:
        return {f"{self.section}_saturated_time": "s", **(sequence.summaries(self) if self.brake else {})}

    @property
    def ledger_kinds(self) -> dict:
        return {self.work_state: "work"}

    @property
    def columns(self) -> dict:
        name = self.section
        out = {f"{name}_reference": ("rad/s", f"the speed controller {name} asks of shaft {self.measures}"),
               f"{name}_error": ("rad/s", f"reference less the speed of shaft {self.measures}"),
               f"{name}_output": ("N*m", f"torque controller {name} asks for, within its limits"),
               f"{name}_torque": ("N*m", f"torque controller {name} drives shaft {self.drives} with (its output, "
                                         "lagged where it has a torque lag)")}
        if self.has_integral:
            out[f"{name}_integral"] = ("rad/s", f"the state of controller {name}'s integral part (Modelica's I.y)")
        if self.reference_block:
            out[f"{self.reference_block}_output"] = ("rad/s", f"the output of signal block {self.reference_block}: "
                                                              f"the reference of controller {name}")
        return out

    @property
    def event_kinds(self) -> tuple:
        name = self.section
        return ((f"{name}_stop",) if self.has_stop else ()) + \
            ((f"{name}_emergency_stop",) if self.has_scheduled_stop else ())

    def boundaries(self) -> tuple:  # the stop command and the emergency stop: the steps of their tables
        return ((self.stopping_times[-1],) if self.has_stop else ()) + \
            ((self.emergency_stop_at,) if self.has_scheduled_stop else ())

    def boundary_events(self, t) -> tuple:
        name = self.section
        return (((f"{name}_stop", t == self.stopping_times[-1]),) if self.has_stop else ()) + \
            (((f"{name}_emergency_stop", t == self.emergency_stop_at),) if self.has_scheduled_stop else ())

    def tables(self) -> dict:
        out = signal_tables(self, "reference")
        if self.brake:
            out.update({f"{self.section}.stopping": ("stopping_times", "stopping_values"),
                        f"{self.section}.emergency": ("emergency_times", "emergency_values")})
        return out

    @property
    def reference_state(self) -> str:
        return f"{self.section}_reference_speed"

    def reference(self, x):
        """r, rad/s: its signal, or an S-curve's speed (the integral of its acceleration's table, a state)."""
        return x.state(self.reference_state) if self.integrates_reference else signal_at(self, x, "reference")

    def _parts(self, x):
        """(the error, the unlimited output v, the derivative filter's input u) at the instant."""
        reference, speed = self.reference(x), x.speed(self.measures)
        proportional = self.setpoint_weight * reference - speed
        integral = x.state(self.integral_state) if self.has_integral else 0.0
        filtered = self.derivative_setpoint_weight * reference - speed
        derivative = (self.derivative_filter * (filtered - x.state(self.filter_state)) if self.has_derivative
                      else 0.0)
        unlimited = self.gain * (proportional + integral + derivative)
        if self.has_emergency_stop:  # switched off: it asks for nothing (and its integral rests)
            unlimited = jnp.where(sequence.switched_off(self, x), 0.0, unlimited)
        if self.brake:  # its brake applied (a stop's end): it takes its torque away, the brake holds the load
            unlimited = jnp.where(x.state(sequence.counts(self.section)[1]) >= self.close_delay, 0.0, unlimited)
        return reference - speed, unlimited, filtered

    def output(self, x):
        """y, N*m: the unlimited output held within the limits."""
        return jnp.clip(self._parts(x)[1], self.min_torque, self.max_torque)

    def torque(self, x):
        """N*m on the shaft it drives: its output, or the lag's state where it has one; none after an emergency
        stop."""
        return self._applied(x, None if self.has_lag else self.output(x))

    def _applied(self, x, output):
        """The torque on the shaft, its output ``output`` already worked out (None where it has a lag)."""
        torque = x.state(self.torque_state) if self.has_lag else output
        return jnp.where(sequence.switched_off(self, x), 0.0, torque) if self.has_emergency_stop else torque

    def torques(self, x) -> tuple:
        return ((self.drives, self.torque(x)),)

    def states(self) -> dict:
        out = {self.work_state: 0.0}
        if self.integrates_reference:
            out[self.reference_state] = 0.0
        if self.has_lag:
            out[self.torque_state] = self.start_output
        if self.has_integral:
            out[self.integral_state] = self.start_integral
        if self.has_derivative:
            out[self.filter_state] = self.start_filter
        if self.brake:
            out.update({count: 0.0 for count in sequence.counts(self.section)[:2 + 3 * self.has_rope]})
        if self.has_emergency_stop:
            out[sequence.emergency_count(self.section)] = 0.0
        return out

    def rates(self, x) -> dict:
        error, unlimited, filtered = self._parts(x)
        output = jnp.clip(unlimited, self.min_torque, self.max_torque)
        torque = self._applied(x, output)
        out = {self.work_state: torque * x.speed(self.drives)}
        if self.integrates_reference:
            out[self.reference_state] = signal_at(self, x, "reference")
        if self.has_lag:
            out[self.torque_state] = (output - x.state(self.torque_state)) / self.torque_lag
        if self.has_integral:
            rate = (error + (output - unlimited) / (self.gain * self.anti_windup)) / self.integral_time
            out[self.integral_state] = (jnp.where(sequence.switched_off(self, x), 0.0, rate) if self.has_emergency_stop
                                        else rate)
        if self.has_derivative:
            out[self.filter_state] = self.derivative_filter * (filtered - x.state(self.filter_state)) \
                / self.derivative_time
        if self.brake:
            out.update(sequence.rates(self, x, torque))
        return out

    def observations(self, x) -> dict:
        unlimited = self._parts(x)[1]
        upper, lower = self.limit_kinds
        out = {upper: self.max_torque - unlimited, lower: unlimited - self.min_torque}
        return {**out, **sequence.guards(self, x, self.torque(x))} if self.brake else out

    def extremes(self, x) -> dict:
        unlimited = self._parts(x)[1]
        saturated = (unlimited >= self.max_torque) | (unlimited <= self.min_torque)
        out = {f"{self.section}_saturated_time": ("duration", saturated)}
        return {**out, **sequence.extremes(self, x, self.torque(x))} if self.brake else out

    def summary(self, x) -> dict:
        return sequence.final(self, x) if self.brake else {}

    def ledger(self, x) -> dict:
        return {self.work_state: x.state(self.work_state)}

    def outputs(self, x) -> dict:
        name = self.section
        error, unlimited, _ = self._parts(x)
        out = {f"{name}_reference": self.reference(x), f"{name}_error": error,
               f"{name}_output": jnp.clip(unlimited, self.min_torque, self.max_torque), f"{name}_torque": self.torque(x)}
        if self.has_integral:
            out[f"{name}_integral"] = x.state(self.integral_state)
        if self.reference_block:
            out[f"{self.reference_block}_output"] = out[f"{name}_reference"]
        return out

