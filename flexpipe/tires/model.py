"""PAC2002 tyre model (vertical + Magic Formula + relaxation) and the model factory."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe._args import as_path, checked_bool, checked_choice, checked_number
from flexpipe.errors import InputError
from flexpipe.tires import _fast, _keys
from flexpipe.tires.checks import probe_forces
from flexpipe.tires.contact import SlipState, TireModel, WheelForces
from flexpipe.tires.fiala import FialaTire
from flexpipe.tires.pac2002 import MagicFormula, SlipForces, checked_use_mode
from flexpipe.tires.tir import TireProperties, read_tir
from flexpipe.tires.vertical import VerticalModel


@dataclass(frozen=True)
class Pac2002Tire(TireModel):
    """PAC2002 Magic Formula tyre with the :class:`TireModel` interface.

    Attributes
    ----------
    mf : MagicFormula
        Steady-state slip forces (USE_MODE honoured).
    vertical : VerticalModel
        Vertical force law.
    unloaded_radius : float
        R0, m.
    relaxation : bool
        First-order slip relaxation (USE_MODE >= 10) when a state is passed.
    vxlow : float
        Speed floor of the kinematic slip denominators, m/s (VXLOW).
    tyre_side : str
        TYRESIDE of the file ('LEFT', 'RIGHT' or 'SYMMETRIC').
    mirror_all : bool
        True for a negative USE_MODE.
    breff, dreff, freff : float or None
        Effective rolling radius coefficients (None: use ``R0 - rho/3``).
    """

    mf: MagicFormula
    vertical: VerticalModel
    unloaded_radius: float
    relaxation: bool = False
    vxlow: float = 1.0
    tyre_side: str = "LEFT"
    mirror_all: bool = False
    breff: float | None = None
    dreff: float | None = None
    freff: float | None = None

    @classmethod
    def from_properties(cls, props: TireProperties, *, use_mode: int | None = None,
                        relaxation: bool | None = None, vertical_law: str = "auto",
                        pressure: float | None = None) -> Pac2002Tire:
        """Build from a Magic Formula :class:`TireProperties`: ``PAC2002`` or ``MF_05``
        (MF 5.2), or an MF 6.1 / 6.2 fit (FITTYP 61 / 62, :mod:`flexpipe.tires.mf61`).

        Parameters
        ----------
        props : TireProperties
        use_mode : int, optional
            Override of the slip part of USE_MODE (0-4).
        relaxation : bool, optional
            Override of the file's USE_MODE (tens digit >= 1: relaxation).
        vertical_law : {"auto", "linear", "duffing"}
            See :meth:`VerticalModel.from_properties`.
        pressure : float, optional
            Inflation pressure of an MF 6.x tyre, Pa (default: the file's INFLPRES); its
            slip forces, relaxation lengths and vertical stiffness (``1 + PFZ1 dpi``)
            follow it.  An MF 5.2 file has no pressure terms: an error.
        """
        if relaxation is not None:
            relaxation = checked_bool(relaxation, "relaxation")
        if pressure is not None:
            pressure = checked_number(pressure, "pressure (inflation pressure)", lo=0.0,
                                      unit="Pa", key="pressure")
        if not (props.is_mf52 or props.is_mf6):
            raise InputError(
                f"PROPERTY_FILE_FORMAT is '{props.property_file_format}'; the PAC2002 model "
                "evaluates the Magic Formula and reads "
                f"{' or '.join(repr(f) for f in _keys.MF52_FORMATS)} files (Adams PAC2002, "
                "MF-Tyre 5.x) and MF-Tyre/MF-Swift 6.1 / 6.2 fits ([MODEL] FITTYP 61 or 62); "
                "a 'FIALA' file needs model='fiala'",
                file=props.path, line=props.lines.get(("MODEL", "PROPERTY_FILE_FORMAT")),
                key="PROPERTY_FILE_FORMAT")
        if props.is_mf6:
            from flexpipe.tires.mf61 import MagicFormula61
            from flexpipe.tires.vertical import mf6_vertical

            mf = MagicFormula61.from_properties(props, use_mode=use_mode, pressure=pressure)
            vertical = mf6_vertical(props, law=vertical_law, dpi=mf.dpi)
        else:
            if pressure is not None:
                raise InputError(
                    "pressure is given but the file is a Magic Formula 5.2 fit, whose "
                    "equations have no inflation pressure; use an MF 6.1 / 6.2 file "
                    "(FITTYP 61 / 62) or leave pressure out", file=props.path, key="pressure")
            mf = MagicFormula.from_properties(props, use_mode=use_mode)
            vertical = VerticalModel.from_properties(props, law=vertical_law)
        refs = [props.get("VERTICAL", k) for k in ("BREFF", "DREFF", "FREFF")]
        have = any(r is not None for r in refs)
        return cls(
            mf=mf, vertical=vertical,
            unloaded_radius=props.unloaded_radius,
            relaxation=props.relaxation if relaxation is None else relaxation,
            vxlow=props.number("MODEL", "VXLOW", 1.0) or 1.0,
            tyre_side=props.tyre_side, mirror_all=props.use_mode < 0,
            breff=(refs[0] or 0.0) if have else None, dreff=(refs[1] or 0.0) if have else None,
            freff=(refs[2] or 0.0) if have else None)

    def effective_rolling_radius(self, deflection):
        """PAC2002 ``Re = R0 - rho_Fz0 (DREFF atan(BREFF rho_d) + FREFF rho_d)``, m.

        ``rho_Fz0 = FNOMIN / k`` and ``rho_d = rho / rho_Fz0``; ``R0 - rho/3`` when the file has
        none of BREFF, DREFF, FREFF.
        """
        rho = np.maximum(deflection, 0.0)
        if self.breff is None:
            return self.unloaded_radius - rho / 3.0
        rho0 = self.mf.fnomin / self.vertical.k
        rd = rho / rho0
        return self.unloaded_radius - rho0 * (self.dreff * np.arctan(self.breff * rd)
                                              + self.freff * rd)

    def relaxation_lengths(self, Fz, gamma=0.0):
        """(sigma_kappa, sigma_alpha), m, from PTX*/PTY* (nan where absent)."""
        return self.mf.relaxation_lengths(Fz, gamma)

    def slip_forces(self, kappa, alpha, Fz, gamma=0.0, *, vx=None, mirror=False,
                    mu_scale=1.0) -> SlipForces:
        """Steady-state contact forces/moments, W-axes (see :meth:`MagicFormula.forces`)."""
        return self.mf.forces(kappa, alpha, Fz, gamma, vx=vx, mirror=mirror, mu_scale=mu_scale)

    def wheel_forces(self, center, spin_axis, omega, velocity, *, road_height,
                     road_normal=(0.0, 0.0, 1.0), angular_velocity=None, mirror=False,
                     mu_scale=1.0, state: SlipState | None = None, dt: float | None = None):
        """As :meth:`TireModel.wheel_forces`, compiled (:mod:`flexpipe.tires._fast`; the
        NumPy code when ``FLEXPIPE_NO_JIT=1`` or without numba)."""
        kw = dict(road_height=road_height, road_normal=road_normal,
                  angular_velocity=angular_velocity, mirror=mirror, mu_scale=mu_scale,
                  state=state, dt=dt)
        if not _fast.enabled():
            return super().wheel_forces(center, spin_axis, omega, velocity, **kw)
        C = np.atleast_2d(np.asarray(center, dtype=float))
        m = C.shape[0]

        def rows(a, width=0, dtype=float):
            a = np.asarray(a, dtype=dtype)
            shape = (m, width) if width else (m,)
            if a.shape != shape:
                a = np.broadcast_to(a, shape)
            return a if a.flags.c_contiguous else np.ascontiguousarray(a)

        s, n, v = rows(spin_axis, 3), rows(road_normal, 3), rows(velocity, 3)
        has_w = angular_velocity is not None
        w = rows(angular_velocity, 3) if has_w else v
        C = rows(C, 3)
        if self.relaxation and state is not None and (dt is None or not dt >= 0):
            raise InputError("dt >= 0 is required with a relaxation state (0: the force of "
                             "the state as it is)", key="dt")
        st = state if state is not None else SlipState.zeros(m)
        q = self._packed()
        out = np.empty((m, 31))
        bad = _fast.wheel_kernel(q, C, s, n, rows(omega), v, w, has_w, rows(road_height),
                                 rows(mirror, dtype=np.bool_), rows(mu_scale),
                                 rows(st.kappa), rows(st.tan_alpha), state is not None,
                                 float(dt or 0.0), out)
        _fast.check_rows(bad, s)
        new_state = SlipState(out[:, 29].copy(), out[:, 30].copy()) if state is not None \
            else None
        return WheelForces(
            force=out[:, 0:3], moment=out[:, 3:6], contact_point=out[:, 6:9],
            frame=out[:, 9:18].reshape(m, 3, 3), Fx=out[:, 18], Fy=out[:, 19], Fz=out[:, 20],
            Mx=out[:, 21], My=out[:, 22], Mz=out[:, 23], kappa=out[:, 24], alpha=out[:, 25],
            gamma=out[:, 26], deflection=out[:, 27], deflection_rate=out[:, 28],
            state=new_state)

    def _packed(self):
        q = self.__dict__.get("_packed_numbers")
        if q is None:
            q = _fast.pack(self)
            object.__setattr__(self, "_packed_numbers", q)
        return q


#: keyword options of :func:`tire_from_file` per model
_OPTIONS = {"pac2002": ("use_mode", "relaxation", "vertical_law", "pressure"),
            "fiala": ("relaxation", "vertical_law")}


def _check_options(model: str, options: dict) -> None:
    """The ``**options`` of :func:`tire_from_file`, before the file is read."""
    for k in options:
        if k not in _OPTIONS[model]:
            raise InputError(f"unknown option {k!r} of the {model} tyre model; valid: "
                             f"{', '.join(_OPTIONS[model])}", key=k)
    if options.get("relaxation") is not None:
        checked_bool(options["relaxation"], "relaxation")
    if "vertical_law" in options:
        checked_choice(options["vertical_law"], "vertical_law", ("auto", "linear", "duffing"))
    if options.get("use_mode") is not None:
        checked_use_mode(options["use_mode"])
    if options.get("pressure") is not None:
        checked_number(options["pressure"], "pressure (inflation pressure)", lo=0.0,
                       unit="Pa", key="pressure")


def tire_from_file(path, *, model: str = "pac2002", **options) -> TireModel:
    """Read a ``.tir`` file and build a tyre model.

    Parameters
    ----------
    path : str or Path
        Tyre property file.
    model : {"pac2002", "fiala"}
        ``pac2002`` needs a Magic Formula file: PAC2002 or MF_05 (MF 5.2), or an MF 6.1 /
        6.2 fit (FITTYP 61 / 62); ``fiala`` accepts a FIALA file or derives its parameters
        from a Magic Formula file (slip stiffnesses, friction and relaxation lengths at
        FNOMIN).
    **options
        Passed to :meth:`Pac2002Tire.from_properties` / :meth:`FialaTire.from_properties`:
        ``relaxation`` (None or bool), ``vertical_law`` (``"auto"``, ``"linear"``,
        ``"duffing"``), and for PAC2002 ``use_mode`` (None or 0-4, the slip part of
        USE_MODE; see :mod:`flexpipe.tires`) and ``pressure`` (inflation pressure of an
        MF 6.x tyre, Pa; default the file's INFLPRES).

    Returns
    -------
    TireModel
        Checked to give finite forces over the normal operating range
        (:func:`flexpipe.tires.checks.probe_forces`).

    Raises
    ------
    InputError
        A bad argument (named, with the valid values), or a bad file.
    """
    path = as_path(path, "path")
    builders = {"pac2002": Pac2002Tire.from_properties, "fiala": FialaTire.from_properties}
    if not isinstance(model, str) or model not in builders:
        raise InputError(f"unknown tyre model {model!r}; valid: {sorted(builders)}", file=path,
                         key="model")
    _check_options(model, options)
    return tire_from_properties(read_tir(path), builder=builders[model], **options)


def tire_from_properties(props, *, builder=None, **options) -> TireModel:
    """Build and check a tyre model from an already read ``.tir`` file (``props``, from
    :func:`read_tir`; ``builder`` a ``from_properties`` method, default PAC2002): the part
    of :func:`tire_from_file` after the reading, for a caller that also needs ``props``.
    Errors without a file are given the file's name."""
    builder = Pac2002Tire.from_properties if builder is None else builder
    try:
        tire = builder(props, **options)
    except InputError as exc:
        if exc.file is not None:
            raise
        raise InputError(str(exc), file=props.path, key=exc.key) from None
    probe_forces(tire, props.path)
    return tire
