"""The machine at one instant: speeds, accelerations and coupling torques, by name.

What elements read to give their torques, rates and outputs (:class:`Instant`),
and the vector field the integrator steps; the accelerations and the coupling
torques come from the bodies' constrained solve (:mod:`hoistsim.machine.core.bodies`).
"""

from __future__ import annotations

from functools import cached_property

import jax.numpy as jnp

from .bodies import Bodies, Response, product, response
from .element import SLIP_BACKWARD, SLIP_FORWARD
from .layout import Layout, angle_state


def slip_sign(mode):
    """+1 slipping forwards (side a faster), -1 backwards, 0 stuck or open."""
    return jnp.where(mode == SLIP_FORWARD, 1.0, jnp.where(mode == SLIP_BACKWARD, -1.0, 0.0))


class Instant:
    """The machine at (t, y): what elements read (by name) to give their torques, rates and outputs.

    ``modes`` (one per coupling) and ``table`` (name, t -> value) are given by
    the caller, and the pass's :class:`Response` where there is one; the
    accelerations and coupling torques are worked out on demand.
    """

    def __init__(self, layout: Layout, t, y, modes=None, table=None, reply: Response | None = None,
                 sliding=None):
        self.layout = layout
        # each slipping coupling's sliding torque, where the caller sets it (None: its own law)
        self._sliding = sliding
        self.t = t
        self.y = y
        self.modes = modes
        self._table = table
        self._reply = reply
        self._solved = None
        self.body_speeds = y[: len(layout.bodies)]
        self.bodies = Bodies(layout, y)

    # ------------------------------------------------------------------ reading by name

    def state(self, name):
        return self.y[self.layout.state_index(name)]

    def speed(self, shaft):
        body, ratio = self.layout.shaft(shaft)
        return ratio * self.body_speeds[body]

    def angle(self, shaft):
        """Angle the shaft has turned since the start (rad); only for shafts an element declares in angles()."""
        return self.state(angle_state(shaft))

    def acceleration(self, shaft):
        body, ratio = self.layout.shaft(shaft)
        return ratio * self.accelerations[body]

    def table(self, name):
        return self._table(name, self.t)

    def table_at(self, name, t):
        """A table's value at another instant of the segment (a signal's derivatives are taken through it)."""
        return self._table(name, t)

    def mode(self, coupling):
        return self.modes[self.layout.coupling_index(coupling)]

    def relative_speed(self, coupling):
        return self.bodies.relative(self.layout.coupling_index(coupling), self.body_speeds)

    def coupling_torque(self, coupling):
        """Torque the coupling passes from its side a to side b (N*m at its shafts)."""
        return self.coupling_torques[self.layout.coupling_index(coupling)]

    def relative_acceleration(self, coupling):
        return self.bodies.relative(self.layout.coupling_index(coupling), self.accelerations)

    # ------------------------------------------------------------------ the bodies' equations

    @property
    def reply(self) -> Response:
        if self._reply is None:
            self._reply = response(self.layout, self.modes, self.y)
        return self._reply

    @cached_property
    def shaft_torques(self) -> dict:
        """External torques by the shaft they act on (N*m at it), each element asked once."""
        torques: dict = {}
        for element in self.layout.elements:
            for shaft, value in element.torques(self):
                self.layout.shaft(shaft, element)  # a shaft the machine has, or a one-line error
                torques[shaft] = torques.get(shaft, 0.0) + value
        return torques

    def body_torques(self):
        """External torques on the bodies (couplings aside), by equal power: an array."""
        torque = [0.0] * len(self.layout.bodies)
        for shaft, value in self.shaft_torques.items():
            body, ratio = self.layout.shaft(shaft)
            torque[body] = torque[body] + value * ratio
        return jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in torque])

    def _solve(self):
        r = self.reply
        tau = self.body_torques()
        given = self._sliding or [None] * len(self.layout.coupling_elements)
        sigma = [0.0 if not e.can_slip else slip_sign(self.modes[k]) * (e.sliding_torque(self) if given[k] is None
                                                                         else given[k])
                 for k, e in enumerate(self.layout.coupling_elements)]
        sigma = jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in sigma]) if sigma else jnp.zeros(0)
        accel = product(r.accel_from_torque, tau) + product(r.accel_from_sliding, sigma)
        torque = product(r.torque_from_torque, tau) + product(r.torque_from_sliding, sigma)
        if self.bodies.driven:  # what the drives hold moves everything along its columns of the response
            held = jnp.stack([jnp.asarray(self.layout.coupling_elements[k].motion(self)[1], dtype=jnp.float64)
                              for k in self.bodies.driven])
            accel = accel + product(r.accel_from_motion, held)
            torque = torque + product(r.torque_from_motion, held)
        pressed = [k for k, e in enumerate(self.layout.coupling_elements) if e.can_slip and e.pressed_by is not None]
        if pressed:
            # what each passes besides moves everything along its column of the response
            columns = [(r.accel_from_sliding[:, k], r.torque_from_sliding[:, k]) for k in pressed]
            for added, column in zip(self._pressed(pressed, (accel, torque), columns), columns):
                accel = accel + added * column[0]
                torque = torque + added * column[1]
        self._solved = (accel, torque)

    def _pressed(self, pressed, solved, columns):
        """What the faces of couplings pressed by a shaft's torque add to their sliding torques (with their
        slips' signs), solved together (one's pressing torque carries what those beyond it pass to the ground).

        The pressing torque of coupling k, P_k = P0_k + sum_j dP_k/dsigma_j sigma_j, responds to what each
        passes (``solved``: the machine without them, with what presses them besides (``pressed_beside``);
        ``columns``: their responses to a unit of each), and
        k passes sigma_k = s f |P_k| = F_k P_k: with the side fixed by the sign of P0_k (the same as P_k's,
        the factors being positive and the machine passive), sigma = (I - F C)^-1 F P0.
        """
        couplings = self.layout.coupling_elements
        signs = [slip_sign(self.modes[k]) for k in pressed]
        pressing = [self._into(couplings[k].pressed_by, *solved, applied=True) for k in pressed]
        beside = [couplings[k].pressed_beside(self) for k in pressed]  # a constant of the pass's law: with P0
        pressing = [p if b is None else p + s * b for p, b, s in zip(pressing, beside, signs)]
        factor = [s * couplings[k].sliding_per_load(self, jnp.sign(s * p)) * jnp.sign(p)
                  for k, s, p in zip(pressed, signs, pressing)]
        change = [[self._into(couplings[k].pressed_by, *column, applied=False) for column in columns] for k in pressed]
        if len(pressed) == 1:
            return [factor[0] * pressing[0] / (1.0 - change[0][0] * factor[0])]
        f = jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in factor])
        c = jnp.stack([jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in row]) for row in change])
        p0 = jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in pressing])
        added = jnp.linalg.solve(jnp.eye(len(pressed)) - f[:, None] * c, f * p0)
        return [added[i] for i in range(len(pressed))]

    def _into(self, shafts, accel, passed, applied: bool):
        """The torque the rest of a body passes into some of its shafts (N*m at the first): what their
        inertia takes, less the torques applied to them, plus what couplings at them pass on, each
        brought to the first shaft by the speeds' ratio; linear in the accelerations and the coupling
        torques (``applied`` False: their part alone).  ``shafts``: one shaft's name, or a tuple; the shafts parts
        declare as parts of them are theirs (a point on a shaft's rim, a body tied to it)."""
        shafts = self.layout.with_parts((shafts,) if isinstance(shafts, str) else tuple(shafts))
        into = 0.0
        for shaft in shafts:
            body, ratio = self.layout.shaft(shaft)
            inertia = sum((value for e in self.layout.elements for on, value in e.inertias() if on == shaft), 0.0)
            taken = inertia * ratio * accel[body]
            if applied:
                taken = taken - self.shaft_torques.get(shaft, 0.0)
            for k, coupling in enumerate(self.layout.coupling_elements):
                for on, weight in coupling.weights():
                    taken = taken + (weight * passed[k] if on == shaft else 0.0)
            # torque at this shaft, at the first: the power it passes is the same
            into = taken if shaft == shafts[0] else into + taken * ratio / self.layout.shaft(shafts[0])[1]
        return into

    def torque_into(self, shaft):
        """The torque the rest of its body passes into a shaft (N*m at the shaft): what presses a mesh's teeth."""
        return self._into(shaft, self.accelerations, self.coupling_torques, applied=True)

    def held_speeds(self):
        """The relative speed each coupling holds while stuck: a drive's its own (the speed it has, where it
        holds an acceleration alone), every other's zero; None without drives (:func:`keep_momentum`'s)."""
        if not self.bodies.driven:
            return None
        speeds = [0.0] * len(self.layout.coupling_elements)
        for k in self.bodies.driven:
            coupling = self.layout.coupling_elements[k]
            speed = coupling.motion(self)[0]
            speeds[k] = self.relative_speed(coupling.section) if speed is None else speed
        return jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in speeds])

    @property
    def accelerations(self):
        if self._solved is None:
            self._solve()
        return self._solved[0]

    @property
    def coupling_torques(self):
        if self._solved is None:
            self._solve()
        return self._solved[1]

    def kinetic_energy(self):
        return jnp.sum(0.5 * self.bodies.inertia * self.body_speeds**2)

    def kinetic_power(self):
        """d/dt of the kinetic energy (W): I w w' for each body, and 1/2 I' w^3 where an inertia varies."""
        power = jnp.sum(self.bodies.inertia * self.body_speeds * self.accelerations)
        for _, shaft, _, slope in self.bodies.varying():
            power = power + 0.5 * slope * self.speed(shaft) ** 3
        return power


def vector_field(t, y, args):
    """dy/dt: the bodies' accelerations, then every element's state rates."""
    return rates_at(Instant(args.layout, t, y, args.modes, args.segment.table, args.reply), y.dtype)


def rates_at(x: Instant, dtype):
    """dy/dt at an instant already worked out."""
    layout = x.layout
    rates = list(x.accelerations) + [0.0] * (layout.size - len(layout.bodies))
    for element in layout.elements:
        for name, rate in element.rates(x).items():
            rates[layout.state_index(name)] = rate
    for shaft in layout.angle_shafts:
        rates[layout.state_index(angle_state(shaft))] = x.speed(shaft)
    return jnp.stack([jnp.asarray(r, dtype=dtype) for r in rates])
