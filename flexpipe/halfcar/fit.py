"""Identify the half-car parameters the paper does not list from its Table 1.

Fixed by choice (plausible values, see ``cars/halfcar_paper.toml``): body length and
mass, the 10-element uniform mesh and the attachment nodes.  Fitted: the bending
stiffness ``EI``, the front and rear spring rates, one tire rate and one wheel mass
(same tire and wheel front and rear), by least squares on the logarithms of these five
parameters, minimizing the relative errors of the complete model's 8 and the rigid
model's 4 natural frequencies against Table 1.

Run ``python -m flexpipe.halfcar.fit [params.toml]`` to print the fitted values in TOML
form, ready to paste into the data file.
"""

from __future__ import annotations

import argparse
import dataclasses

import numpy as np
from scipy.optimize import least_squares

from flexpipe.halfcar.model import build_model, natural_frequencies
from flexpipe.halfcar.params import HalfCarParams, load_params

NAMES = ("bending_stiffness_N_m2", "front.spring_rate_N_per_m", "rear.spring_rate_N_per_m",
         "tire_rate_N_per_m", "wheel_mass_kg")


def _with(p: HalfCarParams, theta: np.ndarray) -> HalfCarParams:
    EI, k_f, k_r, k_t, m_w = theta
    front = dataclasses.replace(p.front, spring_rate_N_per_m=k_f, tire_rate_N_per_m=k_t,
                                wheel_mass_kg=m_w)
    rear = dataclasses.replace(p.rear, spring_rate_N_per_m=k_r, tire_rate_N_per_m=k_t,
                               wheel_mass_kg=m_w)
    return dataclasses.replace(p, bending_stiffness_N_m2=EI, front=front, rear=rear)


def relative_errors(p: HalfCarParams) -> np.ndarray:
    """Relative errors of the complete (8) and rigid (4) frequencies against Table 1."""
    t_c = np.asarray(p.table1_complete_Hz)
    t_r = np.asarray(p.table1_rigid_Hz)
    f_c = natural_frequencies("complete", p)[: t_c.size]
    f_r = natural_frequencies("rigid", p)[: t_r.size]
    return np.concatenate([f_c / t_c - 1.0, f_r / t_r - 1.0])


def fit_parameters(p: HalfCarParams) -> tuple[HalfCarParams, np.ndarray]:
    """Fit EI, spring rates, tire rate and wheel mass to Table 1.

    Parameters
    ----------
    p : HalfCarParams
        Start values and the fixed parameters.

    Returns
    -------
    fitted : HalfCarParams
    errors : ndarray, shape (12,)
        Remaining relative frequency errors.
    """
    theta0 = np.log([p.bending_stiffness_N_m2, p.front.spring_rate_N_per_m,
                     p.rear.spring_rate_N_per_m, p.front.tire_rate_N_per_m,
                     p.front.wheel_mass_kg])

    def residual(log_theta):
        r = relative_errors(_with(p, np.exp(log_theta)))
        build_model.cache_clear()
        return r

    sol = least_squares(residual, theta0, x_scale=1.0, xtol=1e-12, ftol=1e-12)
    fitted = _with(p, np.exp(sol.x))
    return fitted, relative_errors(fitted)


def main(argv=None) -> int:
    """Command-line entry point: print fitted values and remaining errors."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("params", nargs="?", default=None, help="half-car TOML (default: paper)")
    args = ap.parse_args(argv)
    p = load_params(args.params)
    fitted, err = fit_parameters(p)
    print(f"bending_stiffness_N_m2 = {fitted.bending_stiffness_N_m2:.6g}")
    for name, c in (("front", fitted.front), ("rear", fitted.rear)):
        print(f"[{name}] spring_rate_N_per_m = {c.spring_rate_N_per_m:.6g}  "
              f"tire_rate_N_per_m = {c.tire_rate_N_per_m:.6g}  "
              f"wheel_mass_kg = {c.wheel_mass_kg:.4g}")
    print("relative errors (complete 1-8, rigid 1-4):", np.array2string(err, precision=5))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
