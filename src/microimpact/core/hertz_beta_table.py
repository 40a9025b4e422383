"""Polynomial pieces of the scaled Hertz time integral ``G(u) = B(u; 2/5, 1/2) / u^(2/5)``.

:func:`microimpact.core.special.hertz_beta_scaled` evaluates ``G`` from these tables; this module
holds them and the function that made them (:func:`generate`, which needs :mod:`mpmath`; the tests
run it and compare bit for bit). ``G`` is analytic on ``[0, 1)``, with

* ``G(u) = (1/a) F(a, 1 - b; a + 1; u)``, ``a = 2/5``, ``b = 1/2`` (the hypergeometric form of the
  incomplete beta function, DLMF §8.17(ii), as quoted in SciPy's ``betainc`` documentation), and
* a square-root branch point at ``u = 1`` (the integrand's ``(1 - t)^(-1/2)``), which disappears in
  the variable ``s = (1 - u)^(1/2)``.

So ``[0, U_SPLIT)`` is cut into :data:`PIECES` pieces of width :data:`WIDTH` in ``u`` and
``s`` in ``[0, (1 - U_SPLIT)^(1/2)]`` into pieces of the same width in ``s``. On each piece ``G`` is
interpolated at 24 Chebyshev nodes in 60-digit arithmetic, the Chebyshev series is cut after degree
:data:`DEGREE` (the dropped coefficients are below 1e-17 of ``G``), and rewritten in powers of the
piece's local variable ``x`` in ``[-1, 1]`` (Chebyshev approximation: W. H. Press et al.,
*Numerical Recipes*, 3rd ed., §5.8; DLMF §3.11(ii)). Stored as doubles, a piece is evaluated by
Horner's rule; the tests find the result within a few units in the last place of 60-digit values.
"""

from __future__ import annotations

#: Pieces on each side of the split.
PIECES = 10
#: Width of a piece, in ``u`` below the split and in ``s`` above it (a power of 2: exact scaling).
WIDTH = 1.0 / 16.0
#: Degree of the polynomial on each piece.
DEGREE = 10
#: Below this ``u`` the pieces in ``u`` are used, from it on those in ``s = (1 - u)^(1/2)``.
U_SPLIT = 0.625

#: Coefficients of the pieces in ``u`` and in ``s`` (see :func:`generate` for the layout).
# fmt: off
U_COEFFS = (
    2.5113161677586326, 0.011474548898070867, 0.00016137235200784468, 3.056256791424973e-06, 6.657967885521054e-08, 1.5737073208925364e-09, 3.923981618862251e-11, 1.0160845863650321e-12, 2.7060491959601512e-14, 7.380844022326165e-16, 2.0444179493184665e-17,
    2.5349363232993674, 0.01215897785267785, 0.0001814438541389055, 3.6587426853215625e-06, 8.498922311778422e-08, 2.143727499646654e-09, 5.706880953896474e-11, 1.5781830677361106e-12, 4.4895918660812586e-14, 1.3086247920932094e-15, 3.872990224916896e-17,
    2.5600107566562267, 0.012931561048228823, 0.0002056223938102512, 4.434508482253468e-06, 1.1034863884767102e-07, 2.9842157354691388e-09, 8.521828411699128e-11, 2.5287246446235498e-12, 7.720650300820093e-14, 2.4165327681338763e-15, 7.678200779392735e-17,
    2.5867337112676383, 0.01381105219877438, 0.00023513885140609932, 5.451869836401051e-06, 1.4610926979284338e-07, 4.2593945164268585e-09, 1.3118607331924164e-10, 4.199898917335544e-12, 1.383793752706251e-13, 4.676940096492989e-15, 1.6041753348809125e-16,
    2.6153424690499296, 0.014822073513245031, 0.00027173202293018976, 6.814737250751325e-06, 1.979265470932302e-07, 6.2592879278656774e-09, 2.0924857439794697e-10, 7.27386882222005e-12, 2.6028757430397427e-13, 9.561578389970068e-15, 3.563123206047724e-16,
    2.6461314435829855, 0.015997656569412832, 0.0003179270491507152, 8.686598025496378e-06, 2.754463690273254e-07, 9.520406826110443e-09, 3.4806178314674534e-10, 1.3236915048586464e-11, 5.183371032929048e-13, 2.0856313126395232e-14, 8.508404291127628e-16,
    2.6794726936121003, 0.017383253200096933, 0.00037751244817909273, 1.1335142999475494e-05, 3.959178199113603e-07, 1.5091159218801488e-08, 6.088491652022e-10, 2.556241397035796e-11, 1.1053670579584306e-12, 4.917433754875915e-14, 2.2162611110716317e-15,
    2.7158467911000823, 0.01904333098000252, 0.00045639816322740333, 1.5220145283512825e-05, 5.919876246970344e-07, 2.515969309038955e-08, 1.132608174291037e-09, 5.308194844326101e-11, 2.563023165394326e-12, 1.2752215948141997e-13, 6.42081791095926e-15,
    2.7558911637971986, 0.021072765950680215, 0.0005642522713253696, 2.1178765227576373e-05, 9.298872923372259e-07, 4.4676518459606095e-08, 2.2753657150303317e-09, 1.20702702452254e-10, 6.598688621211895e-12, 3.725588310641032e-13, 2.125186947566562e-14,
    2.8004796057273973, 0.02361774941129024, 0.0007178572900146992, 3.085077219693486e-05, 1.55619648596223e-06, 8.603537074959596e-08, 5.04647782075441e-09, 3.084665137624434e-10, 1.9438027140077458e-11, 1.2691356420192715e-12, 8.351043601565024e-14,
)
S_COEFFS = (
    3.6179954613887366, -0.059731772855218974, 0.001332916620291484, -3.294857978559384e-05, 8.573108979163116e-07, -2.3002984819923088e-08, 6.299543951822853e-10, -1.750505106870862e-11, 4.917650990744348e-13, -1.3964050593902922e-14, 3.984071716449148e-16,
    3.503613012595607, -0.0547697820391828, 0.0011541006113041131, -2.6918410137190803e-05, 6.606763903577672e-07, -1.6718837803254718e-08, 4.3178264873724676e-10, -1.1314383041718193e-11, 2.997239340958541e-13, -8.023285654761041e-15, 2.1584160672928682e-16,
    3.3984845657594818, -0.05045651825521729, 0.0010072054039211929, -2.2238506227988154e-05, 5.165330128197171e-07, -1.2368142366543937e-08, 3.022153444739708e-10, -7.492261427656281e-12, 1.8776704464281202e-13, -4.75405689202183e-15, 1.2098631504770118e-16,
    3.3014303299910854, -0.04667896425851274, 0.0008852495202697531, -1.8556496336498516e-05, 4.0907934131740913e-07, -9.295466392511707e-09, 2.155288170303863e-10, -5.069932780021187e-12, 1.2055760855799014e-13, -2.8955949525764032e-15, 6.991501739631602e-17,
    3.2114712085733266, -0.04334825800453027, 0.0007830333325262451, -1.5623833313191985e-05, 3.277610637078711e-07, -7.0862969989193614e-09, 1.5632114489841154e-10, -3.4983046960377116e-12, 7.913688788351683e-14, -1.8079007377892287e-15, 4.1525266236132234e-17,
    3.127786862219526, -0.040393660700407716, 0.0006966249945753395, -1.3262011645314007e-05, 2.6537971033816045e-07, -5.472179024248694e-09, 1.1512139936115836e-10, -2.4568162688883364e-12, 5.299768516195027e-14, -1.1543784243597097e-15, 2.5282874575693235e-17,
    3.049684022735785, -0.0377582294310501, 0.0006230103315195347, -1.1340728377805473e-05, 2.1693232153704012e-07, -4.27548777860282e-09, 8.59642610878727e-11, -1.7532782989916644e-12, 3.614413650951733e-14, -7.522677074911301e-16, 1.5744614540189636e-17,
    2.976572218760453, -0.035395661295212225, 0.0005598498126467139, -9.76345591189758e-06, 1.78882031413403e-07, -3.376396575622188e-09, 6.500990938821081e-11, -1.2696575067618619e-12, 2.506307981660394e-14, -4.994324796048895e-16, 1.0008679287716462e-17,
    2.9079449458454207, -0.03326795746462895, 0.0005053069260952371, -8.457722570050204e-06, 1.4868934148600483e-07, -2.6926313688267652e-09, 4.9737351442785e-11, -9.318585991909978e-13, 1.7645957700994733e-14, -3.3727743977593564e-16, 6.483581703624304e-18,
    2.8433648927735073, -0.031343670633246896, 0.00045792506525646373, -7.368447053019048e-06, 1.2450483539518613e-07, -2.16678441137668e-09, 3.84612993243579e-11, -6.924284804526507e-13, 1.259914382288813e-14, -2.3137207770084805e-16, 4.273567849790066e-18,
)

# fmt: on


def generate(digits: int = 60, nodes: int = 24):
    """``(U_COEFFS, S_COEFFS)`` computed afresh with :mod:`mpmath` (module docstring).

    Each is a flat tuple of ``PIECES * (DEGREE + 1)`` floats: piece ``k``'s coefficients of
    ``x^0 ... x^DEGREE`` at ``k * (DEGREE + 1)``, where ``x = 2 (t - t_k)/WIDTH - 1`` for ``t`` (``u``
    or ``s``) in ``[t_k, t_k + WIDTH]``, ``t_k = k WIDTH``.
    """
    import mpmath as mp

    with mp.workdps(digits):  # mpmath's working precision, restored on leaving
        a = mp.mpf(2) / 5
        b = mp.mpf(1) / 2

        def g_of_u(u):
            return mp.hyp2f1(a, 1 - b, a + 1, u) / a

        def g_of_s(s):
            return g_of_u(1 - s * s)

        def pieces(f):
            coeffs = []
            half = mp.mpf(WIDTH) / 2
            for k in range(PIECES):
                centre = mp.mpf(WIDTH) * k + half
                theta = [mp.pi * (i + mp.mpf(1) / 2) / nodes for i in range(nodes)]
                values = [f(centre + half * mp.cos(t)) for t in theta]
                cheb = [
                    2 * mp.fsum(v * mp.cos(j * t) for v, t in zip(values, theta)) / nodes for j in range(DEGREE + 1)
                ]
                cheb[0] /= 2
                # powers of x from sum_j c_j T_j(x), with T_{j+1} = 2 x T_j - T_{j-1}
                power = [mp.mpf(0)] * (DEGREE + 1)
                t_prev, t_cur = [mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]
                for j, c in enumerate(cheb):
                    tj = t_prev if j == 0 else t_cur
                    for i, ti in enumerate(tj):
                        power[i] += c * ti
                    if j >= 1:
                        t_next = [mp.mpf(0)] + [2 * x for x in t_cur]
                        for i, x in enumerate(t_prev):
                            t_next[i] -= x
                        t_prev, t_cur = t_cur, t_next
                coeffs.extend(float(p) for p in power)
            return tuple(coeffs)

        return pieces(g_of_u), pieces(g_of_s)


def _source() -> str:  # pragma: no cover - run by hand: python -m microimpact.core.hertz_beta_table
    u, s = generate()

    def block(name, values):
        lines = [f"{name} = ("]
        step = DEGREE + 1
        for k in range(PIECES):
            lines.append("    " + " ".join(f"{v!r}," for v in values[k * step : (k + 1) * step]))
        lines.append(")")
        return "\n".join(lines)

    return block("U_COEFFS", u) + "\n" + block("S_COEFFS", s)


if __name__ == "__main__":  # pragma: no cover
    print(_source())
