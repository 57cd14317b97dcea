"""Closed forms for the singular points of Painleve's rod (scenes/painleve-rod.toml).

Independent of detach: sympy from the scene's formulas. Run
`python3 tests/data/painleve_singular.py`; tests/it/singular.rs uses the
closed forms printed here.

theta_ddot = f/g, f = 3 U (cos t - mu sin t), g = l V,
U = l sin(t) w^2 - g0, V = 1 + 3 cos^2 t - 3 mu sin t cos t.
Singular points: V = 0 and U = 0. Desingularised field G = (g w, f),
DG = [[g_t w, g_w w + g], [f_t, f_w]]; g_w = 0 and g = 0 at the point, so
DG is lower triangular: lambda1 = l V'(t) w (across), lambda2 = f_w (along).
"""

import sympy as sp

t, w, mu, l, g0, T = sp.symbols("theta theta_dot mu l g T", real=True)
U = l * sp.sin(t) * w**2 - g0
V = 1 + 3 * sp.cos(t) ** 2 - 3 * mu * sp.sin(t) * sp.cos(t)
f = 3 * U * (sp.cos(t) - mu * sp.sin(t))
g = l * V

# V / cos^2 in T = tan(theta).
assert sp.simplify(V / sp.cos(t) ** 2 - (sp.tan(t) ** 2 - 3 * mu * sp.tan(t) + 4)) == 0
print("V/cos^2 = T^2 - 3 mu T + 4, T = tan(theta)")
roots = sp.solve(sp.Eq(T**2 - 3 * mu * T + 4, 0), T)
print("tan(theta) roots:", roots, "(real iff 9 mu^2 - 16 > 0, mu > 4/3)")
print("theta_dot = +-sqrt(g/(l sin theta))")

DG = sp.Matrix([[sp.diff(g * w, t), sp.diff(g * w, w)], [sp.diff(f, t), sp.diff(f, w)]])
print("DG =", DG)
lam1 = sp.diff(g, t) * w  # across
lam2 = sp.diff(f, w)  # along
print("lambda1 =", sp.simplify(lam1), " lambda2 =", sp.simplify(lam2))

# |lambda1| = |lambda2| at a point: the ratio V'/(6 sin (cos - mu sin)),
# written in T over cos^2, with T^2 = 3 mu T - 4 substituted.
ratio_num = sp.expand(3 * mu * T**2 - 6 * T - 3 * mu)  # V'(theta)/cos^2
ratio_den = sp.expand(6 * T * (1 - mu * T))  # 6 sin (cos - mu sin)/cos^2
assert sp.simplify(
    (sp.diff(V, t) / sp.cos(t) ** 2).subs(sp.sin(t), T * sp.cos(t)) - ratio_num
) == 0
assert sp.simplify(
    (6 * sp.sin(t) * (sp.cos(t) - mu * sp.sin(t)) / sp.cos(t) ** 2).subs(sp.sin(t), T * sp.cos(t))
    - ratio_den
) == 0
red = lambda e: sp.expand(sp.rem(sp.Poly(e, T), sp.Poly(T**2 - 3 * mu * T + 4, T)).as_expr())
conditions = []
for sign in (1, -1):
    e = red(ratio_num - sign * ratio_den)  # linear in T
    Tsol = sp.solve(e, T)
    print("sign", sign, ": T =", Tsol)
    for s in Tsol:
        cond = sp.factor(sp.numer(sp.together((s**2 - 3 * mu * s + 4))))
        print("   on V = 0 iff", cond, "= 0")
        conditions.append((s, cond))

mu_c = sp.Rational(8, 1) / (3 * sp.sqrt(3))
poly = 27 * mu**4 - 37 * mu**2 - 64
print("27 mu^4 - 37 mu^2 - 64 =", sp.factor(poly), "; positive root", sp.solve(poly, mu))
assert sp.simplify(poly.subs(mu, mu_c)) == 0
print("mu_c = 8/(3 sqrt 3) =", sp.N(mu_c, 30))
Tl = sp.simplify(min(roots, key=lambda r: sp.N(r.subs(mu, mu_c))).subs(mu, mu_c))
print("at mu_c the lower root is tan(theta) =", sp.nsimplify(Tl), "=", sp.N(Tl, 20))
print("13 mu/(9 mu^2 - 4) at mu_c =", sp.nsimplify(sp.simplify((13 * mu / (9 * mu**2 - 4)).subs(mu, mu_c))))

# Types at mu = 3/2, l = 1, g = 981/100: node at the lower root, saddle at
# the upper one; which eigenvalue is slower at the node.
vals = {mu: sp.Rational(3, 2), l: 1, g0: sp.Rational(981, 100)}
for r in roots:
    th = sp.atan(r.subs(vals))
    for s in (1, -1):
        wd = s * sp.sqrt(vals[g0] / (vals[l] * sp.sin(th)))
        at = {**vals, t: th, w: wd}
        a, b = sp.N(lam1.subs(at), 25), sp.N(lam2.subs(at), 25)
        kind = "saddle" if a * b < 0 else ("stable node" if a < 0 else "unstable node")
        print(f"mu=3/2 theta={sp.N(th, 25)} theta_dot={sp.N(wd, 25)}: lambda1={a} lambda2={b} {kind}")
# Equilibria (theta_dot = 0, cos - mu sin = 0): tan(theta) = 1/mu, V = 1 there,
# J = [[0, 1], [F_theta, 0]], F_theta = 3 g sqrt(1 + mu^2)/l: a saddle.
th = sp.atan(1 / mu)
Ft = sp.simplify(sp.diff(f / g, t).subs(w, 0).subs(t, th))
print("equilibrium tan(theta) = 1/mu, F_theta =", sp.simplify(Ft), "; V there =", sp.simplify(V.subs(t, th)))
