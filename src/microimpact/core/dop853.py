"""The Dormand-Prince 8(5,3) Runge-Kutta tableau: the method of Hairer's code DOP853.

Prince & Dormand (1981), "High order embedded Runge-Kutta formulae", J. Comput. Appl. Math. 7, 67;
the code DOP853 of Hairer, Norsett & Wanner (*Solving Ordinary Differential Equations I*, 2nd ed.,
Springer 1993, Sec. II.10), whose coefficients :mod:`scipy.integrate` tabulates in
``scipy/integrate/_ivp/dop853_coefficients.py`` (read here; ``tests/core/test_dop853.py`` checks
every value below against that table and the tableau's order conditions). Each value is that
table's decimal rounded to the nearest double.

``A{s}_{j}``: the stage matrix (stage ``s`` from the slopes of stages ``j < s``; zeros left out),
``B{j}``: the eighth-order weights (scipy's ``B``, the stage matrix's row 12), ``E5_{j}`` and
``E3_{j}``: the fifth- and third-order error estimators (scipy's ``E5`` and ``E3``), which Hairer's
code combines as ``|err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2)``. Stage ``j`` is evaluated at
``t + C_j h``; the autonomous equations this project integrates do not need ``C``.

:func:`step` is one step of the method for the equations of motion the models integrate, written
once over the tableau; each model passes its own right-hand side and measures the step's error
with its own scale (:func:`hairer_error` is Hairer's measure).
"""

from __future__ import annotations

import math

from ._jit import jitable

A1_0 = 0.05260015195876773
A2_0 = 0.0197250569845379
A2_1 = 0.0591751709536137
A3_0 = 0.02958758547680685
A3_2 = 0.08876275643042054
A4_0 = 0.2413651341592667
A4_2 = -0.8845494793282861
A4_3 = 0.924834003261792
A5_0 = 0.037037037037037035
A5_3 = 0.17082860872947386
A5_4 = 0.12546768756682242
A6_0 = 0.037109375
A6_3 = 0.17025221101954405
A6_4 = 0.06021653898045596
A6_5 = -0.017578125
A7_0 = 0.03709200011850479
A7_3 = 0.17038392571223998
A7_4 = 0.10726203044637328
A7_5 = -0.015319437748624402
A7_6 = 0.008273789163814023
A8_0 = 0.6241109587160757
A8_3 = -3.3608926294469414
A8_4 = -0.868219346841726
A8_5 = 27.59209969944671
A8_6 = 20.154067550477894
A8_7 = -43.48988418106996
A9_0 = 0.47766253643826434
A9_3 = -2.4881146199716677
A9_4 = -0.590290826836843
A9_5 = 21.230051448181193
A9_6 = 15.279233632882423
A9_7 = -33.28821096898486
A9_8 = -0.020331201708508627
A10_0 = -0.9371424300859873
A10_3 = 5.186372428844064
A10_4 = 1.0914373489967295
A10_5 = -8.149787010746927
A10_6 = -18.52006565999696
A10_7 = 22.739487099350505
A10_8 = 2.4936055526796523
A10_9 = -3.0467644718982196
A11_0 = 2.273310147516538
A11_3 = -10.53449546673725
A11_4 = -2.0008720582248625
A11_5 = -17.9589318631188
A11_6 = 27.94888452941996
A11_7 = -2.8589982771350235
A11_8 = -8.87285693353063
A11_9 = 12.360567175794303
A11_10 = 0.6433927460157636
B0 = 0.054293734116568765
B5 = 4.450312892752409
B6 = 1.8915178993145003
B7 = -5.801203960010585
B8 = 0.3111643669578199
B9 = -0.1521609496625161
B10 = 0.20136540080403034
B11 = 0.04471061572777259
E5_0 = 0.01312004499419488
E5_5 = -1.2251564463762044
E5_6 = -0.4957589496572502
E5_7 = 1.6643771824549864
E5_8 = -0.35032884874997366
E5_9 = 0.3341791187130175
E5_10 = 0.08192320648511571
E5_11 = -0.022355307863886294
E3_0 = -0.18980075407240762
E3_5 = 4.450312892752409
E3_6 = 1.8915178993145003
E3_7 = -5.801203960010585
E3_8 = -0.4226823213237919
E3_9 = -0.1521609496625161
E3_10 = 0.20136540080403034
E3_11 = 0.02265179219836082


@jitable
def step(rates, x, v, w, h, p):
    """One step of length ``h`` of DOP853 for ``x' = v``, ``v' = a``, ``w' = d`` from ``(x, v, w)``,
    with ``(a, d) = rates(x, v, p)`` (``p``: the model's parameters, passed through; ``w``, such as
    the work dissipated so far, does not enter the rates, so it needs no stages of its own).

    Returns ``(x, v, w)`` at the step's end and the fifth- and third-order error estimators of
    ``x`` and ``v`` (``e5x, e5v, e3x, e3v``, per unit step: the error is ``h`` times them), from
    which each model measures the error on its own scale (:func:`hairer_error`). Every sum is
    written out left to right over the stages whose coefficients are not zero, so a compiled step
    and the Python one add the same products in the same order: the same bits.
    """
    a0, d0 = rates(x, v, p)
    x1 = x + h * (A1_0 * v)
    v1 = v + h * (A1_0 * a0)
    a1, d1 = rates(x1, v1, p)
    x2 = x + h * (A2_0 * v + A2_1 * v1)
    v2 = v + h * (A2_0 * a0 + A2_1 * a1)
    a2, d2 = rates(x2, v2, p)
    x3 = x + h * (A3_0 * v + A3_2 * v2)
    v3 = v + h * (A3_0 * a0 + A3_2 * a2)
    a3, d3 = rates(x3, v3, p)
    x4 = x + h * (A4_0 * v + A4_2 * v2 + A4_3 * v3)
    v4 = v + h * (A4_0 * a0 + A4_2 * a2 + A4_3 * a3)
    a4, d4 = rates(x4, v4, p)
    x5 = x + h * (A5_0 * v + A5_3 * v3 + A5_4 * v4)
    v5 = v + h * (A5_0 * a0 + A5_3 * a3 + A5_4 * a4)
    a5, d5 = rates(x5, v5, p)
    x6 = x + h * (A6_0 * v + A6_3 * v3 + A6_4 * v4 + A6_5 * v5)
    v6 = v + h * (A6_0 * a0 + A6_3 * a3 + A6_4 * a4 + A6_5 * a5)
    a6, d6 = rates(x6, v6, p)
    x7 = x + h * (A7_0 * v + A7_3 * v3 + A7_4 * v4 + A7_5 * v5 + A7_6 * v6)
    v7 = v + h * (A7_0 * a0 + A7_3 * a3 + A7_4 * a4 + A7_5 * a5 + A7_6 * a6)
    a7, d7 = rates(x7, v7, p)
    x8 = x + h * (A8_0 * v + A8_3 * v3 + A8_4 * v4 + A8_5 * v5 + A8_6 * v6 + A8_7 * v7)
    v8 = v + h * (A8_0 * a0 + A8_3 * a3 + A8_4 * a4 + A8_5 * a5 + A8_6 * a6 + A8_7 * a7)
    a8, d8 = rates(x8, v8, p)
    x9 = x + h * (A9_0 * v + A9_3 * v3 + A9_4 * v4 + A9_5 * v5 + A9_6 * v6 + A9_7 * v7 + A9_8 * v8)
    v9 = v + h * (A9_0 * a0 + A9_3 * a3 + A9_4 * a4 + A9_5 * a5 + A9_6 * a6 + A9_7 * a7 + A9_8 * a8)
    a9, d9 = rates(x9, v9, p)
    x10 = x + h * (A10_0 * v + A10_3 * v3 + A10_4 * v4 + A10_5 * v5 + A10_6 * v6 + A10_7 * v7 + A10_8 * v8 + A10_9 * v9)
    v10 = v + h * (
        A10_0 * a0 + A10_3 * a3 + A10_4 * a4 + A10_5 * a5 + A10_6 * a6 + A10_7 * a7 + A10_8 * a8 + A10_9 * a9
    )
    a10, d10 = rates(x10, v10, p)
    x11 = x + h * (
        A11_0 * v
        + A11_3 * v3
        + A11_4 * v4
        + A11_5 * v5
        + A11_6 * v6
        + A11_7 * v7
        + A11_8 * v8
        + A11_9 * v9
        + A11_10 * v10
    )
    v11 = v + h * (
        A11_0 * a0
        + A11_3 * a3
        + A11_4 * a4
        + A11_5 * a5
        + A11_6 * a6
        + A11_7 * a7
        + A11_8 * a8
        + A11_9 * a9
        + A11_10 * a10
    )
    a11, d11 = rates(x11, v11, p)
    xn = x + h * (B0 * v + B5 * v5 + B6 * v6 + B7 * v7 + B8 * v8 + B9 * v9 + B10 * v10 + B11 * v11)
    vn = v + h * (B0 * a0 + B5 * a5 + B6 * a6 + B7 * a7 + B8 * a8 + B9 * a9 + B10 * a10 + B11 * a11)
    wn = w + h * (B0 * d0 + B5 * d5 + B6 * d6 + B7 * d7 + B8 * d8 + B9 * d9 + B10 * d10 + B11 * d11)
    e5x = E5_0 * v + E5_5 * v5 + E5_6 * v6 + E5_7 * v7 + E5_8 * v8 + E5_9 * v9 + E5_10 * v10 + E5_11 * v11
    e5v = E5_0 * a0 + E5_5 * a5 + E5_6 * a6 + E5_7 * a7 + E5_8 * a8 + E5_9 * a9 + E5_10 * a10 + E5_11 * a11
    e3x = E3_0 * v + E3_5 * v5 + E3_6 * v6 + E3_7 * v7 + E3_8 * v8 + E3_9 * v9 + E3_10 * v10 + E3_11 * v11
    e3v = E3_0 * a0 + E3_5 * a5 + E3_6 * a6 + E3_7 * a7 + E3_8 * a8 + E3_9 * a9 + E3_10 * a10 + E3_11 * a11
    return xn, vn, wn, e5x, e5v, e3x, e3v


@jitable
def hairer_error(h, e5x, e5v, e3x, e3v, sx, sv):
    """The error of a step of length ``h`` from :func:`step`'s estimators as Hairer's code measures it:
    root mean square over ``x`` and ``x'`` of ``|err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2)``, each
    component divided by its scale ``sx``, ``sv`` (the model's tolerance times its size); 0 where
    both estimators vanish."""
    e5x /= sx  # (squares written as products: Python's ``** 2`` is libm's pow, not always x * x)
    e5v /= sv
    e3x /= sx
    e3v /= sv
    e5 = e5x * e5x + e5v * e5v
    e3 = e3x * e3x + e3v * e3v
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt(2.0 * (e5 + 0.01 * e3))
