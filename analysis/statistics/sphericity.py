"""Contrasts of a within-subject effect and the sphericity of their covariance (Mauchly; Greenhouse–Geisser;
Huynh–Feldt).

For a design whose factors have k_1, ..., k_m levels (C = Π k_f cells, first factor slowest), the effect of a
set E of factors is carried by the C × d matrix

    L_E = ⊗_f  ( Q_f  if f ∈ E  else  1_f / √k_f ),     d = Π_{f ∈ E} (k_f − 1),

where Q_f is any k_f × (k_f − 1) matrix of orthonormal contrasts (columns orthonormal and orthogonal to 1).
A subject's scores on the effect are z_s = L_Eᵀ y_s. With M the d × d sample covariance of the z_s over the n
subjects (Maxwell & Delaney 2004, ch. 13; O'Brien & Kaiser 1985):

* Mauchly's (1940) W = det M / (tr M / d)^d, χ² = −(n − 1)·ρ·ln W with ρ = 1 − (2d² + d + 2) / (6d(n − 1)),
  on d(d + 1)/2 − 1 df, p with the second-order term
  ω₂ = (d + 2)(d − 1)(d − 2)(2d³ + 6d² + 3C + 2) / (288 ((n − 1) d ρ)²):
  p = P(χ²_f > χ²) + ω₂ (P(χ²_{f+4} > χ²) − P(χ²_f > χ²)). Using C (all cells of the design) in ω₂ follows
  R's ``mauchly.test`` and ``car``/``afex`` (it only matters from four levels on);
* Greenhouse & Geisser (1959): ε_GG = (tr M)² / (d · tr M²), between 1/d and 1;
* Huynh & Feldt (1976): ε_HF = (n d ε_GG − 2) / (d (n − 1 − d ε_GG)), as R and ``afex`` print it (it can
  exceed 1; corrected degrees of freedom use min(ε_HF, 1)); undefined (NaN) when n − 1 ≤ d ε_GG.

Every statistic is invariant to the choice of Q_f; an effect with d = 1 is spherical by construction.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import reduce

import numpy as np
from scipy import stats


def orthonormal_contrasts(k: int) -> np.ndarray:
    """A k × (k − 1) matrix with orthonormal columns, each orthogonal to the vector of ones."""
    q, _ = np.linalg.qr(np.column_stack([np.ones(k), np.eye(k)[:, : k - 1]]))
    return np.asarray(q[:, 1:])


def effect_contrasts(levels: Sequence[int], effect: Sequence[int]) -> np.ndarray:
    """L_E for the factors at positions ``effect`` of a design with ``levels[f]`` levels per factor."""
    parts = [orthonormal_contrasts(k) if f in effect else np.full((k, 1), 1 / math.sqrt(k))
             for f, k in enumerate(levels)]
    return np.asarray(reduce(np.kron, parts))


@dataclass(frozen=True, slots=True)
class Sphericity:
    """Mauchly's test and the ε estimates of one effect; ``w``, ``chi2``, ``df`` and ``p`` are NaN when the test
    does not apply (d = 1) or cannot be computed (``note`` says why)."""

    d: int
    w: float
    chi2: float
    df: float
    p: float
    eps_gg: float
    eps_hf: float
    note: str = ""


def sphericity(scores: np.ndarray, n_cells: int) -> Sphericity:
    """Sphericity of the effect whose contrast scores (n subjects × d) are ``scores``."""
    n, d = scores.shape
    if d == 1 or n < 2:
        return covariance_sphericity(np.zeros((d, d)), max(n - 1, 0), n_cells)
    return covariance_sphericity(np.atleast_2d(np.cov(scores, rowvar=False, ddof=1)), n - 1, n_cells)


def covariance_sphericity(m: np.ndarray, dof: int, n_cells: int) -> Sphericity:
    """Sphericity from the d × d error covariance ``m`` of an effect's contrast scores on ``dof`` degrees of freedom
    (n − 1 with n participants in one group; N − G with G groups of a mixed design, the pooled within-group
    covariance, as R's ``car``/``afex`` compute it). The formulas above with n − 1 = ``dof``."""
    d = m.shape[0]
    nan = float("nan")
    if d == 1:
        return Sphericity(1, nan, nan, nan, nan, 1.0, 1.0)
    if dof < 1:
        return Sphericity(d, nan, nan, nan, nan, nan, nan, "fewer than 2 participants")
    trace = float(np.trace(m))
    if trace <= 0:
        return Sphericity(d, nan, nan, nan, nan, nan, nan, "no error variance")
    gg = trace**2 / (d * float(np.trace(m @ m)))
    hf = ((dof + 1) * d * gg - 2) / (d * (dof - d * gg)) if dof - d * gg > 0 else nan
    if dof < d:
        return Sphericity(d, nan, nan, nan, nan, gg, hf,
                          f"Mauchly's test needs more participants than the effect's {d} df")
    sign, logdet = np.linalg.slogdet(m)
    log_w = logdet - d * math.log(trace / d) if sign > 0 else -math.inf
    rho = 1 - (2 * d**2 + d + 2) / (6 * d * dof)
    chi2 = -dof * rho * log_w
    df = d * (d + 1) / 2 - 1
    omega2 = ((d + 2) * (d - 1) * (d - 2) * (2 * d**3 + 6 * d**2 + 3 * n_cells + 2)
              / (288 * (dof * d * rho) ** 2))
    p1, p2 = stats.chi2.sf(chi2, df), stats.chi2.sf(chi2, df + 4)
    p = float(min(1.0, max(0.0, p1 + omega2 * (p2 - p1))))
    return Sphericity(d, math.exp(log_w), float(chi2), float(df), p, gg, hf)
