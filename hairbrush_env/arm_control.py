"""Cartesian control of the arm: damped-least-squares IK plus straight-stroke planning.

The thesis keeps the brush "parallel to the ground" while it is pulled down through the hair; here that is
the *level* orientation :data:`LEVEL_QUAT` (tool frame = world frame: bristles along +x, rows along +y,
up = +z).  :class:`CartesianController` turns a tool-centre-point pose into arm joint targets for the
arm's position servos; :func:`plan_stroke` makes the constant-speed waypoints of one stroke.
"""

from __future__ import annotations

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["DEFAULT_SITE", "LEVEL_QUAT", "CartesianController", "plan_stroke"]

#: Identity orientation: the brush held level, bristles pointing along world +x.
LEVEL_QUAT = np.array([1.0, 0.0, 0.0, 0.0])
#: TCP of the brush attached with ``prefix="brush/"`` (see ``assets/brush/README.md``).
DEFAULT_SITE = "brush/brush_tcp"


class CartesianController:
    """Damped-least-squares IK for the serial chain that carries ``site``.

    The controlled joints are the hinge/slide joints on the kinematic path from ``site``'s body to the
    world (the arm's six joints; the brush's tine joints are *below* the TCP and are ignored), and the
    actuators are those whose transmission is one of these joints.

    Parameters
    ----------
    model
        Compiled model containing the arm (and usually the brush attached to it).
    site
        Name of the controlled site, e.g. ``"brush/brush_tcp"`` or the arm's ``"attachment_site"``.
    damping
        DLS damping λ (m, rad).  Solutions stay bounded near singularities; near a regular solution its
        effect is negligible because λ² = 1e-4 ≪ σ_min(J)² ≈ 0.01–0.1 in this workspace.
    max_iters, pos_tol, rot_tol
        Iteration budget and convergence tolerances (m, rad) of :meth:`solve`.
    max_step
        Largest joint change per iteration (rad); keeps the Newton steps inside the region where the
        linearisation holds when the target is far from the current pose.
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        *,
        site: str = DEFAULT_SITE,
        damping: float = 1e-2,
        max_iters: int = 100,
        pos_tol: float = 1e-5,
        rot_tol: float = 1e-4,
        max_step: float = 0.2,
    ) -> None:
        if damping < 0:
            raise ValueError(f"damping must be >= 0, got {damping}")
        self.model = model
        self.site_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, site)
        if self.site_id < 0:
            raise ValueError(f"site {site!r} not found in the model")
        self.damping = float(damping)
        self.max_iters = int(max_iters)
        self.pos_tol = float(pos_tol)
        self.rot_tol = float(rot_tol)
        self.max_step = float(max_step)

        # Joints on the path site -> world, ordered base first.
        joints: list[int] = []
        body = int(model.site_bodyid[self.site_id])
        while body > 0:
            adr, num = int(model.body_jntadr[body]), int(model.body_jntnum[body])
            for j in range(adr + num - 1, adr - 1, -1):
                if int(model.jnt_type[j]) in (
                    int(mujoco.mjtJoint.mjJNT_HINGE),
                    int(mujoco.mjtJoint.mjJNT_SLIDE),
                ):
                    joints.append(j)
                else:
                    raise ValueError(f"joint {j} on the chain of {site!r} is not a hinge/slide joint")
            body = int(model.body_parentid[body])
        if not joints:
            raise ValueError(f"site {site!r} is not carried by any actuated chain")
        self.joint_ids = np.array(joints[::-1], dtype=int)
        self.qpos_adr = model.jnt_qposadr[self.joint_ids].copy()
        self.dof_adr = model.jnt_dofadr[self.joint_ids].copy()
        limited = model.jnt_limited[self.joint_ids].astype(bool)
        rng = model.jnt_range[self.joint_ids]
        self.q_lower = np.where(limited, rng[:, 0], -np.inf)
        self.q_upper = np.where(limited, rng[:, 1], np.inf)

        # Actuator driving each joint (position servos: gain kp, bias -kp q - kv qdot).
        act = np.full(len(joints), -1, dtype=int)
        for a in range(model.nu):
            if int(model.actuator_trntype[a]) == int(mujoco.mjtTrn.mjTRN_JOINT):
                hit = np.flatnonzero(self.joint_ids == model.actuator_trnid[a, 0])
                if hit.size:
                    act[hit[0]] = a
        if np.any(act < 0):
            missing = [
                mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, int(j)) for j in self.joint_ids[act < 0]
            ]
            raise ValueError(f"joints without a joint-transmission actuator: {missing}")
        self.actuator_ids = act
        kp = model.actuator_gainprm[act, 0]
        kv = -model.actuator_biasprm[act, 2]
        # Velocity feed-forward gain: MuJoCo's position servo damps the *absolute* joint velocity
        # (force = kp (u - q) - kv qdot), so at constant qdot it lags by kv/kp * qdot.  Offsetting the
        # set-point by the same amount cancels that lag exactly.
        self.velocity_ff = np.where(kp > 0, kv / np.where(kp > 0, kp, 1.0), 0.0)
        ctrl_limited = model.actuator_ctrllimited[act].astype(bool)
        crange = model.actuator_ctrlrange[act]
        self.ctrl_lower = np.where(ctrl_limited, crange[:, 0], -np.inf)
        self.ctrl_upper = np.where(ctrl_limited, crange[:, 1], np.inf)

        # Scratch state so that solve() never touches the caller's MjData.
        self._scratch = mujoco.MjData(model)
        n = len(joints)
        self._jacp = np.zeros((3, model.nv))
        self._jacr = np.zeros((3, model.nv))
        self._jac = np.zeros((6, n))
        self._err = np.zeros(6)
        self._quat = np.zeros(4)
        self._qerr = np.zeros(4)
        self._eye = np.eye(6)

    @property
    def n_joints(self) -> int:
        return len(self.joint_ids)

    # ------------------------------------------------------------------ kinematics helpers
    def _forward(self, qpos: NDArray[np.float64]) -> None:
        s = self._scratch
        s.qpos[:] = qpos
        mujoco.mj_kinematics(self.model, s)
        mujoco.mj_comPos(self.model, s)

    def _error(self, target_pos: NDArray[np.float64], target_quat: NDArray[np.float64]) -> None:
        s = self._scratch
        self._err[:3] = target_pos - s.site_xpos[self.site_id]
        mujoco.mju_mat2Quat(self._quat, s.site_xmat[self.site_id])
        # q_err = q_target * conj(q_site) is the world-frame rotation taking the site to the target;
        # its rotation vector is the angular error in the world frame, matching mj_jacSite's jacr.
        mujoco.mju_negQuat(self._quat, self._quat)
        mujoco.mju_mulQuat(self._qerr, target_quat, self._quat)
        mujoco.mju_quat2Vel(self._err[3:], self._qerr, 1.0)

    def _jacobian(self) -> NDArray[np.float64]:
        mujoco.mj_jacSite(self.model, self._scratch, self._jacp, self._jacr, self.site_id)
        self._jac[:3] = self._jacp[:, self.dof_adr]
        self._jac[3:] = self._jacr[:, self.dof_adr]
        return self._jac

    def site_pose(self, data: mujoco.MjData) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """World position and quaternion (w, x, y, z) of the controlled site in ``data`` (after forward)."""
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, data.site_xmat[self.site_id])
        return data.site_xpos[self.site_id].copy(), quat

    def arm_qpos(self, data: mujoco.MjData) -> NDArray[np.float64]:
        """Current positions of the controlled joints."""
        return data.qpos[self.qpos_adr].copy()

    # ------------------------------------------------------------------ IK
    def solve(
        self,
        data: mujoco.MjData,
        target_pos: ArrayLike,
        target_quat: ArrayLike | None = None,
        *,
        q_init: ArrayLike | None = None,
    ) -> NDArray[np.float64]:
        """Joint targets that put the site at ``target_pos`` with orientation ``target_quat``.

        Parameters
        ----------
        data
            Source of the non-arm state (and of the initial guess when ``q_init`` is None); not modified.
        target_pos
            World position (m).
        target_quat
            World orientation (w, x, y, z); default :data:`LEVEL_QUAT` (brush parallel to the ground).
        q_init
            Initial guess for the controlled joints, e.g. the previous solution while tracking a path
            (keeps consecutive solutions on the same branch and converges in one or two iterations).

        Returns
        -------
        ndarray, shape (n_joints,)
            Joint positions within the joint limits.  If the target is unreachable this is the damped
            least-squares compromise; check it with :meth:`pose_error`.
        """
        p = np.asarray(target_pos, dtype=float).reshape(3)
        quat = LEVEL_QUAT if target_quat is None else np.asarray(target_quat, dtype=float).reshape(4)
        quat = quat / np.linalg.norm(quat)
        qpos = data.qpos.copy()
        if q_init is not None:
            qpos[self.qpos_adr] = np.asarray(q_init, dtype=float)
        qpos[self.qpos_adr] = np.clip(qpos[self.qpos_adr], self.q_lower, self.q_upper)
        lam2 = self.damping**2
        for _ in range(self.max_iters):
            self._forward(qpos)
            self._error(p, quat)
            if np.linalg.norm(self._err[:3]) < self.pos_tol and np.linalg.norm(self._err[3:]) < self.rot_tol:
                break
            jac = self._jacobian()
            dq = jac.T @ np.linalg.solve(jac @ jac.T + lam2 * self._eye, self._err)
            biggest = np.abs(dq).max()
            if biggest > self.max_step:
                dq *= self.max_step / biggest
            # Clipping to the limits (rather than a null-space or QP treatment) is enough here: the
            # brushing workspace is well inside the joint ranges.
            qpos[self.qpos_adr] = np.clip(qpos[self.qpos_adr] + dq, self.q_lower, self.q_upper)
        return qpos[self.qpos_adr].copy()

    def pose_error(
        self, data: mujoco.MjData, target_pos: ArrayLike, target_quat: ArrayLike | None = None
    ) -> tuple[float, float]:
        """Position error (m) and orientation error (rad) of the site in ``data`` w.r.t. a target."""
        pos, quat = self.site_pose(data)
        target = LEVEL_QUAT if target_quat is None else np.asarray(target_quat, dtype=float)
        qerr = np.zeros(4)
        mujoco.mju_negQuat(quat, quat)
        mujoco.mju_mulQuat(qerr, target / np.linalg.norm(target), quat)
        angle = 2.0 * np.arctan2(np.linalg.norm(qerr[1:]), abs(qerr[0]))
        return float(np.linalg.norm(np.asarray(target_pos, dtype=float) - pos)), float(angle)

    def joint_velocity(
        self, data: mujoco.MjData, q: ArrayLike, lin_vel: ArrayLike, ang_vel: ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """Joint velocities giving the site twist (``lin_vel``, ``ang_vel``; world frame) at joints ``q``."""
        qpos = data.qpos.copy()
        qpos[self.qpos_adr] = np.asarray(q, dtype=float)
        self._forward(qpos)
        jac = self._jacobian()
        omega = np.zeros(3) if ang_vel is None else np.asarray(ang_vel, dtype=float)
        twist = np.concatenate([np.asarray(lin_vel, dtype=float), omega])
        return jac.T @ np.linalg.solve(jac @ jac.T + self.damping**2 * self._eye, twist)

    # ------------------------------------------------------------------ servo commands
    def ctrl(self, q: ArrayLike, qdot: ArrayLike | None = None) -> NDArray[np.float64]:
        """Actuator set-points for joint targets ``q`` (and optional joint velocity feed-forward ``qdot``)."""
        u = np.asarray(q, dtype=float).copy()
        if qdot is not None:
            u += self.velocity_ff * np.asarray(qdot, dtype=float)
        return np.clip(u, self.ctrl_lower, self.ctrl_upper)

    def apply(self, data: mujoco.MjData, q: ArrayLike, qdot: ArrayLike | None = None) -> None:
        """Write :meth:`ctrl` into ``data.ctrl`` for the arm's actuators (other actuators untouched)."""
        data.ctrl[self.actuator_ids] = self.ctrl(q, qdot)

    def track(
        self,
        data: mujoco.MjData,
        target_pos: ArrayLike,
        target_vel: ArrayLike | None = None,
        target_quat: ArrayLike | None = None,
        *,
        q_init: ArrayLike | None = None,
    ) -> NDArray[np.float64]:
        """One control tick: solve IK, add the velocity feed-forward, write ``data.ctrl``; returns ``q``."""
        q = self.solve(data, target_pos, target_quat, q_init=q_init)
        qdot = None if target_vel is None else self.joint_velocity(data, q, target_vel)
        self.apply(data, q, qdot)
        return q


def plan_stroke(start: ArrayLike, end: ArrayLike, speed: float, dt: float) -> NDArray[np.float64]:
    """Waypoints of a straight stroke from ``start`` to ``end`` at constant ``speed``.

    Parameters
    ----------
    start, end
        World positions (m) of the TCP; a brushing stroke is ``end = start - (0, 0, length)``.
    speed
        Path speed (m/s), > 0.
    dt
        Waypoint spacing in time (s), > 0; usually the control period.

    Returns
    -------
    ndarray, shape (n, 3)
        ``points[k]`` is the target at time ``k * dt``: spaced ``speed * dt`` apart, first = ``start``,
        last = ``end`` exactly (the final step may be shorter).  The target velocity is
        ``speed * (end - start) / |end - start|`` throughout.
    """
    if not speed > 0:
        raise ValueError(f"speed must be > 0, got {speed}")
    if not dt > 0:
        raise ValueError(f"dt must be > 0, got {dt}")
    a = np.asarray(start, dtype=float).reshape(3)
    b = np.asarray(end, dtype=float).reshape(3)
    length = float(np.linalg.norm(b - a))
    if length == 0.0:
        return a[None].copy()
    s = np.arange(0.0, length, speed * dt)
    s = np.append(s, length) if length - s[-1] > 1e-12 else s
    return a + np.outer(s / length, b - a)
