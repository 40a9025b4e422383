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
"""

from __future__ import annotations

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

#: The weights above as tuples over the stages they use (0 and 5 to 11, in that order), so that an
#: integrator combines its stages with one function of a tuple.
B = (B0, B5, B6, B7, B8, B9, B10, B11)
E5 = (E5_0, E5_5, E5_6, E5_7, E5_8, E5_9, E5_10, E5_11)
E3 = (E3_0, E3_5, E3_6, E3_7, E3_8, E3_9, E3_10, E3_11)
