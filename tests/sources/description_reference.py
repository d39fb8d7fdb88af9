"""An independent statics of a `Description` with Pinocchio calls only (not mechkit's core): closure and
coupling rows, their Jacobian, gravity and springs, the actuation matrix, assembly by damped least
squares, the holding efforts, the mobility and the idle freedoms.

Conventions: the Pinocchio model's q and v; closure rows in the world frame; at rest
`S u + J^T lambda = g(q) - passive(q)` (g: Pinocchio's generalised gravity, passive: the springs).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import scipy.linalg

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def _perpendicular(axis: np.ndarray) -> np.ndarray:
    """Two unit vectors (rows) perpendicular to a unit axis and to each other."""
    return scipy.linalg.null_space(axis.reshape(1, 3)).T


class Statics:
    """The statics of a description (see the module docstring)."""

    def __init__(self, desc, held: tuple[str, ...] = ()):
        """Args: desc: a `Description` with `model`; held: one-freedom joints held by a stop (an effort
        column each, after the actuators)."""
        self.desc, self.model = desc, desc.model
        self.data = self.model.createData()
        self.frames = {
            c.name: (self.model.getFrameId(c.frame_a), self.model.getFrameId(c.frame_b)) for c in desc.closures
        }
        for a, b in self.frames.values():
            assert a < self.model.nframes and b < self.model.nframes
        tendons = {a.name: a for a in desc.actuators}
        columns = [
            sum(c * self._unit(j) for j, c in tendons[name].joints) if name in tendons else self._unit(name)
            for name in desc.actuated
        ] + [self._unit(j) for j in held]
        self.S = np.column_stack(columns) if columns else np.zeros((self.model.nv, 0))

    def _unit(self, joint: str) -> np.ndarray:
        e = np.zeros(self.model.nv)
        e[self._v(joint)] = 1.0
        return e

    def _v(self, joint: str) -> int:
        j = self.model.getJointId(joint)
        assert self.model.joints[j].nv == 1, joint
        return self.model.joints[j].idx_v

    def configuration(self, values: dict) -> np.ndarray:
        """q from joint values: a one-freedom joint's value, a universal joint's two angles, a ball's
        rotation vector, a free-flyer's position and rotation vector (the form of `Description.guess`);
        other joints neutral."""
        q = pin.neutral(self.model)
        for name, value in values.items():
            jm = self.model.joints[self.model.getJointId(name)]
            v = np.atleast_1d(np.asarray(value, dtype=float))
            if jm.nq == len(v):
                q[jm.idx_q : jm.idx_q + jm.nq] = v
            else:  # a ball (rotation vector) or a free-flyer (position, rotation vector)
                q[jm.idx_q : jm.idx_q + jm.nq - 4] = v[:-3]
                q[jm.idx_q + jm.nq - 4 : jm.idx_q + jm.nq] = pin.Quaternion(pin.exp3(v[-3:])).coeffs()
        return q

    def value(self, q: np.ndarray, joint: str) -> float:
        """A one-freedom joint's value (rad or m)."""
        return float(q[self.model.joints[self.model.getJointId(joint)].idx_q])

    def _poses(self, q: np.ndarray) -> None:
        pin.framesForwardKinematics(self.model, self.data, q)
        pin.computeJointJacobians(self.model, self.data, q)

    def rows(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(residual, Jacobian (rows, nv)) of every closure and coupling at q; the Jacobian is exact on
        the closed configuration (rotation rows span the same space as the residual's derivative)."""
        self._poses(q)
        res, jac = [], []
        for c in self.desc.closures:
            fa, fb = self.frames[c.name]
            A, B = self.data.oMf[fa], self.data.oMf[fb]
            Ja = pin.getFrameJacobian(self.model, self.data, fa, LWA)
            Jb = pin.getFrameJacobian(self.model, self.data, fb, LWA)
            d, dJ, w = B.translation - A.translation, Jb[:3] - Ja[:3], Jb[3:] - Ja[3:]
            error = A.rotation @ pin.log3(A.rotation.T @ B.rotation)  # world frame
            if c.kind == "spherical":
                r, j = [d], [dJ]
            elif c.kind == "weld":
                r, j = [d, error], [dJ, w]
            elif c.kind == "revolute":
                n = _perpendicular(A.rotation @ c.axis)
                r, j = [d, n @ error], [dJ, n @ w]
            elif c.kind == "prismatic":
                n = _perpendicular(A.rotation @ c.axis)
                turn = np.array([np.cross(u, d) for u in n])
                r, j = [n @ d, error], [n @ dJ + turn @ Ja[3:], w]
            elif c.kind == "hooke":
                a, b = A.rotation @ c.axis_a, B.rotation @ c.axis_b
                r, j = [d, [a @ b]], [dJ, [np.cross(a, b) @ (Ja[3:] - Jb[3:])]]
            else:
                raise AssertionError(c.kind)
            res += r
            jac += j
        for k in self.desc.couplings:
            x_l = sum(c * self.value(q, j) for j, c in k.leader) - k.leader_ref
            dP = sum(i * p * x_l ** (i - 1) for i, p in enumerate(k.polynomial) if i)
            row = sum(c * self._unit(j) for j, c in k.follower) - dP * sum(
                (c * self._unit(j) for j, c in k.leader), np.zeros(self.model.nv)
            )
            x_f = sum(c * self.value(q, j) for j, c in k.follower) - k.follower_ref
            res.append([x_f - sum(p * x_l**i for i, p in enumerate(k.polynomial))])
            jac.append([row])
        if not res:
            return np.zeros(0), np.zeros((0, self.model.nv))
        return np.concatenate([np.ravel(r) for r in res]), np.vstack([np.atleast_2d(r) for r in jac])

    def generalised(self, q: np.ndarray) -> np.ndarray:
        """g(q) - passive(q) at rest (N m or N per velocity coordinate)."""
        g = pin.computeGeneralizedGravity(self.model, self.data, q).copy()
        for s in self.desc.springs:
            j = self.model.getJointId(s.joint)
            if self.model.joints[j].nv == 1:
                g[self._v(s.joint)] -= s.preload - s.stiffness * (self.value(q, s.joint) - s.reference)
        return g

    def assemble(self, q: np.ndarray, fixed: dict[str, float], tol: float = 1e-12, iters: int = 100) -> np.ndarray:
        """Close every loop and coupling with the `fixed` joints at their values: Gauss-Newton steps of
        least norm (singular values below 1e-13 of the largest dropped: idle and redundant directions)."""
        for _ in range(iters):
            r, J = self.rows(q)
            r = np.concatenate([r, [self.value(q, j) - v for j, v in fixed.items()]])
            J = np.vstack([J] + [self._unit(j) for j in fixed])
            if np.max(np.abs(r)) < tol:
                return q
            q = pin.integrate(self.model, q, -np.linalg.lstsq(J, r, rcond=1e-13)[0])
        raise AssertionError(f"no assembly: residual {np.max(np.abs(r)):.2e}")

    def efforts(self, q: np.ndarray) -> tuple[np.ndarray, float]:
        """(efforts u (least squares), the unbalanced generalised force |S u + J^T lambda - (g - passive)|)."""
        _, J = self.rows(q)
        A = np.hstack([self.S, J.T])
        b = self.generalised(q)
        x = np.linalg.lstsq(A, b, rcond=None)[0]
        return x[: self.S.shape[1]], float(np.linalg.norm(A @ x - b))

    def equilibrium(self, q: np.ndarray, fixed: dict[str, float], tol: float = 1e-12, iters: int = 60) -> np.ndarray:
        """A closed configuration, the `fixed` joints at their values, where the efforts hold (Newton on
        q, u and lambda together; the passive freedoms settle where the springs balance gravity), to
        `tol` times the largest generalised force."""
        q = self.assemble(q, fixed)
        nu, n = self.S.shape[1], self.model.nv
        ncons = self.rows(q)[0].size
        x = np.linalg.lstsq(np.hstack([self.S, self.rows(q)[1].T]), self.generalised(q), rcond=None)[0]

        def residual(q, x):
            r, J = self.rows(q)
            fix = [self.value(q, j) - v for j, v in fixed.items()]
            return np.concatenate([r, fix, self.S @ x[:nu] + J.T @ x[nu:] - self.generalised(q)])

        scale = max(1.0, float(np.max(np.abs(self.generalised(q)))))
        for _ in range(iters):
            F = residual(q, x)
            if np.max(np.abs(F)) < tol * scale:
                return q
            h = 1e-7
            Jq = np.column_stack(
                [
                    (
                        residual(pin.integrate(self.model, q, h * e), x)
                        - residual(pin.integrate(self.model, q, -h * e), x)
                    )
                    / (2 * h)
                    for e in np.eye(n)
                ]
            )
            Jx = np.vstack([np.zeros((ncons + len(fixed), nu + ncons)), np.hstack([self.S, self.rows(q)[1].T])])
            K = np.hstack([Jq, Jx])
            step = -np.linalg.lstsq(K, F, rcond=1e-12)[0]
            q, x = self.assemble(pin.integrate(self.model, q, step[:n]), fixed), x + step[n:]
        raise AssertionError(f"no equilibrium: residual {np.max(np.abs(F)):.2e}")

    def mobility(self, q: np.ndarray, tol: float = 1e-9) -> int:
        """nv - rank of the closure and coupling Jacobian."""
        _, J = self.rows(q)
        return self.model.nv - (np.linalg.matrix_rank(J, tol * max(1.0, np.max(np.abs(J)))) if J.size else 0)

    def idle(self, q: np.ndarray, tol: float = 1e-9) -> dict[str, int]:
        """Body -> motions that move it alone among the bodies with mass: rank(T) - rank(T without it),
        T the world twists of the joints carrying mass over the null space of the Jacobian; a body is
        named by the first BODY frame on its joint."""
        _, J = self.rows(q)
        null = scipy.linalg.null_space(J, rcond=tol) if J.size else np.eye(self.model.nv)
        self._poses(q)
        names = {}
        for f in self.model.frames:
            if f.type == pin.FrameType.BODY and f.parentJoint > 0 and self.model.inertias[f.parentJoint].mass > 0:
                names.setdefault(f.parentJoint, f.name)
        twists = {
            names[j]: pin.getJointJacobian(self.model, self.data, j, pin.ReferenceFrame.WORLD) @ null for j in names
        }
        scale = max(1.0, max(float(np.max(np.abs(t))) for t in twists.values()))

        def rank(bodies):
            return int(np.linalg.matrix_rank(np.vstack([twists[k] for k in bodies]), tol * scale)) if bodies else 0

        full = rank(list(twists))
        alone = {k: full - rank([o for o in twists if o != k]) for k in twists}
        return {k: n for k, n in alone.items() if n}
