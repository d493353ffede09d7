"""Reading a compiled rod: its centerline, length and moving bodies, whichever kind built it."""

from __future__ import annotations

import mujoco
import numpy as np

from .flex import GHOST_FRACTION
from .spec import RodKind, polyline_length

__all__ = ["RodView", "rod_length", "rod_vertices"]


class RodView:
    """Cached index lookup for one rod of a compiled model (chain or flex, told apart by the model).

    Parameters
    ----------
    model : mujoco.MjModel
        Compiled model containing a rod built by :func:`hairbrush_env.rods.add_rod`.
    name : str
        Rod name.

    Attributes
    ----------
    kind : {"chain", "flex"}
    n_points : int
        Rows of :meth:`vertices`: row ``k`` is ``points[k]`` of the :class:`~hairbrush_env.rods.RodSpec`.
    bodies : np.ndarray
        Ids of the rod's moving bodies (chain: one per edge; flex: one per free vertex), e.g. for body forces.

    Notes
    -----
    Positions are MuJoCo's kinematics (``data.xpos``/``xmat`` for chains, ``data.flexvert_xpos`` for flexes),
    filled in by ``mj_forward``/``mj_step``: after ``mj_step`` they belong to the state *before* the step; call
    ``mj_forward`` after ``MjData`` creation or ``mj_setState`` before reading. A clamped flex's pinned ghost vertex
    is skipped. A chain's last vertex is the tip of its last capsule.
    """

    def __init__(self, model: mujoco.MjModel, name: str) -> None:
        self.name = name
        fid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_FLEX, name)
        if fid >= 0:
            self._init_flex(model, int(fid))
        elif mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, f"{name}_0") >= 0:
            self._init_chain(model)
        else:
            raise KeyError(f"no rod named {name!r} (neither a flex nor a chain body {name}_0)")

    def _init_flex(self, model: mujoco.MjModel, fid: int) -> None:
        if model.flex_dim[fid] != 1:
            raise ValueError(f"flex {self.name!r} is not a rod (dim={model.flex_dim[fid]})")
        self.kind: RodKind = "flex"
        adr = int(model.flex_vertadr[fid])
        num = int(model.flex_vertnum[fid])
        # add_flex_rod's clamped rods start with ghost + root, both on the parent body; the ghost edge is the only
        # edge that short (GHOST_FRACTION of its neighbour), which tells it apart from a rod pinned by flexcomp.
        vbodies = model.flex_vertbodyid[adr : adr + num]
        eadr = int(model.flex_edgeadr[fid])
        lengths = model.flexedge_length0[eadr : eadr + int(model.flex_edgenum[fid])]
        self.has_ghost = bool(
            num >= 3 and vbodies[0] == vbodies[1] and lengths[0] < 2.0 * GHOST_FRACTION * lengths[1]
        )
        start = adr + (1 if self.has_ghost else 0)
        self._rows = slice(start, adr + num)
        self.n_points = adr + num - start
        parent = vbodies[0]
        self.bodies = np.array([b for b in vbodies if b != parent or not self.has_ghost], dtype=int)
        self.tip_body = int(vbodies[-1])

    def _init_chain(self, model: mujoco.MjModel) -> None:
        self.kind = "chain"
        self.has_ghost = False
        ids = []
        while (b := mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, f"{self.name}_{len(ids)}")) >= 0:
            ids.append(b)
        self.bodies = np.array(ids, dtype=int)
        last = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, f"{self.name}_{len(ids) - 1}")
        self._tip_length = 2.0 * float(model.geom_size[last, 1])  # capsule size[1] is the half length
        self.n_points = len(ids) + 1
        self.tip_body = int(ids[-1])

    def vertices(self, data: mujoco.MjData) -> np.ndarray:
        """Current centerline, an ``(n_points, 3)`` array in world coordinates (a new array)."""
        if self.kind == "flex":
            return data.flexvert_xpos[self._rows].copy()
        out = np.empty((self.n_points, 3))
        out[:-1] = data.xpos[self.bodies]
        out[-1] = out[-2] + data.xmat[self.tip_body].reshape(3, 3)[:, 0] * self._tip_length
        return out

    def length(self, data: mujoco.MjData) -> float:
        """Current centerline length [m]."""
        return polyline_length(self.vertices(data))

    def set_tip_force(self, data: mujoco.MjData, force: np.ndarray) -> None:
        """Apply the world-frame ``force`` [N] at the rod's free end through ``xfrc_applied``.

        A chain's tip is off its last body's centre of mass, where ``xfrc_applied`` acts, so the moment of the
        offset is added; it depends on the current pose, so call this before every step.
        """
        f = np.asarray(force, dtype=float)
        data.xfrc_applied[self.tip_body, :3] = f
        if self.kind == "chain":
            tip = self.vertices(data)[-1]
            data.xfrc_applied[self.tip_body, 3:] = np.cross(tip - data.xipos[self.tip_body], f)


def rod_vertices(model: mujoco.MjModel, data: mujoco.MjData, name: str) -> np.ndarray:
    """Current centerline of rod ``name`` as an ``(n, 3)`` array (see :class:`RodView`; cache one in loops)."""
    return RodView(model, name).vertices(data)


def rod_length(model: mujoco.MjModel, data: mujoco.MjData, name: str) -> float:
    """Current centerline length of rod ``name`` [m]."""
    return RodView(model, name).length(data)
