"""The mechanism of W. Bu (2012), Section 5, and the computations on it: the data
of the example, inverse kinematics, Jacobians, the unit-load compliance and a tiny
2-D frame stiffness method. The helpers of bu_reference.py (see its docstring and
docs/notes/bu-reference.md); needs only numpy.
"""
import numpy as np


# --------------------------------------------------------------------------
# Data of the example (paper Table 2 and text of Section 5)
# --------------------------------------------------------------------------
L12, L23, L34, L3P, L4P, L45, L56, L16 = 0.9, 1.0, 0.8, 0.4, 0.4, 1.0, 0.6, 1.0
BASE_J1 = np.array([-0.5, 0.0])   # base joints, from J1P = (0.5, 1.1) at P1
BASE_J6 = np.array([+0.5, 0.0])   # |J1J6| = 1.0, symmetric about the y axis
POSES = {"P1": 1.1, "P2": 1.2, "P3": 1.3, "P4": 1.4, "P5": 1.5}  # P = (0, y), phi = 0
JOINTS = ["J1", "J2", "J3", "J4", "J5", "J6"]

# Section data used for the secondary (axial / shear) terms; the paper's
# tables are bending only, so these only enter the "all terms" comparison.
R_SEC = 0.02          # m; the paper's "r = 0.002 m" is a typo (833 = 4/3*(0.5/0.02)^2)
NU = 0.3              # Poisson ratio -> G = E / (2 (1 + nu))
K_SHEAR = 10.0 / 9.0  # shear form factor of a solid circle (gamma = k F_Q / (G A))
E_MOD = 1.0           # results are reported in units of E*I_z, so E cancels
I_SEC = np.pi * R_SEC ** 4 / 4
A_SEC = np.pi * R_SEC ** 2
G_MOD = E_MOD / (2 * (1 + NU))
SEGS = ["J1J2", "J2J3", "J3P", "J4P", "J4J5", "J5J6"]   # column order of Tables 3, 4


# --------------------------------------------------------------------------
# 1. Inverse kinematics
# --------------------------------------------------------------------------
def e(a):
    return np.array([np.cos(a), np.sin(a)])


def ang(v):
    return np.arctan2(v[1], v[0])


def cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


def circle_intersections(A, ra, B, rb):
    d = np.linalg.norm(B - A)
    if d > ra + rb or d < abs(ra - rb):
        raise ValueError("unreachable")
    a = (ra ** 2 - rb ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(max(ra ** 2 - a ** 2, 0.0))
    u = (B - A) / d
    n = np.array([-u[1], u[0]])
    return A + a * u + h * n, A + a * u - h * n


def ik(y, phi=0.0, branch=("out", "out")):
    """Joint positions for P = (0, y), platform angle phi.

    branch[0] for the left dyad (J2), branch[1] for the right dyad (J5):
    'out' = the elbow on the outer side (J2 with the smaller x, J5 with the
    larger x); this is the branch that reproduces the printed Jacobians.
    """
    P = np.array([0.0, y])
    J3 = P - L3P * e(phi)
    J4 = P + L4P * e(phi)
    c2 = circle_intersections(BASE_J1, L12, J3, L23)
    c5 = circle_intersections(BASE_J6, L56, J4, L45)
    J2 = min(c2, key=lambda p: p[0]) if branch[0] == "out" else max(c2, key=lambda p: p[0])
    J5 = max(c5, key=lambda p: p[0]) if branch[1] == "out" else min(c5, key=lambda p: p[0])
    return {"J1": BASE_J1.copy(), "J2": J2, "J3": J3, "P": P, "J4": J4, "J5": J5, "J6": BASE_J6.copy()}


def joint_coords(pts):
    """Joint coordinates with the sign conventions of eqs. 21-22.

    left chain (base -> platform) J1 -> J2 -> J3: q1 = abs. angle of J1J2,
    q2 = angle of J2J3 minus angle of J1J2, q3 = phi minus angle of J2J3;
    right chain (base -> platform) J6 -> J5 -> J4: q6 = abs. angle of J6J5,
    q5 = angle of J5J4 minus angle of J6J5, q4 = phi minus angle of J5J4.
    All counter-clockwise positive, rates are relative rates of the distal
    body with respect to the proximal body, as in eqs. 21 and 22.
    """
    a1 = ang(pts["J2"] - pts["J1"])
    a2 = ang(pts["J3"] - pts["J2"])
    phi = ang(pts["J4"] - pts["J3"])
    a6 = ang(pts["J5"] - pts["J6"])
    a5 = ang(pts["J4"] - pts["J5"])
    wrap = lambda t: (t + np.pi) % (2 * np.pi) - np.pi
    return {"q1": a1, "q2": wrap(a2 - a1), "q3": wrap(phi - a2),
            "q6": a6, "q5": wrap(a5 - a6), "q4": wrap(phi - a5), "phi": phi}


# --------------------------------------------------------------------------
# 2. Jacobians
# --------------------------------------------------------------------------
def screw_col(pts, j):
    """Column of eq. 21/22: twist [omega, vPx, vPy] at P of a unit rate of joint j."""
    r = pts["P"] - pts[j]
    return np.array([1.0, -r[1], r[0]])


def jac_analytic(pts, act):
    """J_act: [phi', vPx, vPy] = J_act @ (actuated rates).  Paper eqs. 21-25
    generalised: M rows = rows of J123^-1 (left joints) or J456^-1 (right
    joints) for the actuated joints, J = M^-1."""
    SL = np.column_stack([screw_col(pts, j) for j in ("J1", "J2", "J3")])
    SR = np.column_stack([screw_col(pts, j) for j in ("J4", "J5", "J6")])
    inv_rows = {}
    for k, j in enumerate(("J1", "J2", "J3")):
        inv_rows[j] = np.linalg.inv(SL)[k]
    for k, j in enumerate(("J4", "J5", "J6")):
        inv_rows[j] = np.linalg.inv(SR)[k]
    M = np.vstack([inv_rows[j] for j in act])
    return np.linalg.inv(M), M


def jac_loop_closure(pts, act):
    """Independent generic route: solve the loop-closure rate equations
    S_L w_L - S_R w_R = 0 together with w_act = unit vectors; twist = S_L w_L."""
    SL = np.column_stack([screw_col(pts, j) for j in ("J1", "J2", "J3")])
    SR = np.column_stack([screw_col(pts, j) for j in ("J4", "J5", "J6")])
    order = ["J1", "J2", "J3", "J4", "J5", "J6"]
    A = np.zeros((6, 6))
    A[:3, :3] = SL
    A[:3, 3:] = -SR
    J = np.zeros((3, 3))
    for c, ja in enumerate(act):
        A2 = A.copy()
        b = np.zeros(6)
        for r, jj in enumerate(act):
            A2[3 + r, :] = 0.0
            A2[3 + r, order.index(jj)] = 1.0
        b[3 + c] = 1.0
        w = np.linalg.solve(A2, b)
        J[:, c] = SL @ w[:3]
    return J


def fk_123(q1, q2, q3):
    """Serial left chain (J4, J5, J6 passive): platform pose [phi, Px, Py]."""
    a1 = q1
    a2 = q1 + q2
    phi = a2 + q3
    J2 = BASE_J1 + L12 * e(a1)
    J3 = J2 + L23 * e(a2)
    P = J3 + L3P * e(phi)
    return np.array([phi, P[0], P[1]])


def fk_126(q1, q2, q6, J4_ref):
    """Closure FK with J1, J2, J6 given: J3 from the left dyad, J5 from q6,
    J4 = intersection of circles (J3, 0.8) and (J5, 1.0) nearest the reference."""
    J2 = BASE_J1 + L12 * e(q1)
    J3 = J2 + L23 * e(q1 + q2)
    J5 = BASE_J6 + L56 * e(q6)
    c = circle_intersections(J3, L34, J5, L45)
    J4 = min(c, key=lambda p: np.linalg.norm(p - J4_ref))
    phi = ang(J4 - J3)
    P = 0.5 * (J3 + J4)  # J3P = J4P = 0.4, P is the midpoint of J3J4
    return np.array([phi, P[0], P[1]])


def jac_fd(pts, act, h=1e-6):
    q = joint_coords(pts)
    if act == ("J1", "J2", "J3"):
        f = lambda v: fk_123(*v)
        q0 = np.array([q["q1"], q["q2"], q["q3"]])
    elif act == ("J1", "J2", "J6"):
        f = lambda v: fk_126(v[0], v[1], v[2], pts["J4"])
        q0 = np.array([q["q1"], q["q2"], q["q6"]])
    else:
        raise NotImplementedError
    J = np.zeros((3, 3))
    for c in range(3):
        dq = np.zeros(3)
        dq[c] = h
        J[:, c] = (f(q0 + dq) - f(q0 - dq)) / (2 * h)
    return J


def K_actuated(J, kI=(1.0, 1.0, 1.0)):
    Ji = np.linalg.inv(J)
    return Ji.T @ np.diag(kI) @ Ji


# --------------------------------------------------------------------------
# 4. Unit-load (virtual force) method, statically determinate structures
# --------------------------------------------------------------------------
def seg_ends(pts, s):
    return {"J1J2": ("J1", "J2"), "J2J3": ("J2", "J3"), "J3P": ("J3", "P"),
            "J4P": ("J4", "P"), "J4J5": ("J4", "J5"), "J5J6": ("J5", "J6")}[s]


def section_forces(pts, s, side_loads):
    """Internal forces of straight segment s from the resultant of the forces
    acting on one chosen side (same side for all load cases, so products of
    two load cases are consistent).  side_loads: list of (point, F(2), M).
    Returns M at end A, M at end B, N, V (N along A->B, V along its normal)."""
    a, b = seg_ends(pts, s)
    A, B = pts[a], pts[b]
    t = (B - A) / np.linalg.norm(B - A)
    n = np.array([-t[1], t[0]])
    F = sum((fl[1] for fl in side_loads), np.zeros(2))
    mom = lambda X: sum(cross2(fl[0] - X, fl[1]) + fl[2] for fl in side_loads)
    return np.array([mom(A), mom(B), F @ t, F @ n])


def unit_load_forces(pts, act, w):
    """w = (Mz, Fx, Fy) applied to the platform at P.  Returns dict seg -> forces."""
    Mz, Fx, Fy = w
    F = np.array([Fx, Fy])
    P = pts["P"]
    zero = [(P, np.zeros(2), 0.0)]
    out = {}
    if tuple(act) == ("J1", "J2", "J3"):
        # Frozen J1, J2, J3: ground-J1J2-J2J3-platform is one cantilever clamped
        # at J1.  The right dyad J4-J5-J6 (three pins) consists of two two-force
        # bars meeting at the unloaded pin J5: node J5 equilibrium
        # T45 e45 + T56 e56 = 0 with e45 not parallel to e56 gives T45 = T56 = 0.
        e45 = (pts["J5"] - pts["J4"]) / L45
        e56 = (pts["J6"] - pts["J5"]) / L56
        T = np.linalg.solve(np.column_stack([e45, -e56]), np.zeros(2))
        load = [(P, F, Mz)]
        out["J1J2"] = section_forces(pts, "J1J2", load)   # side: towards P
        out["J2J3"] = section_forces(pts, "J2J3", load)
        out["J3P"] = section_forces(pts, "J3P", load)
        out["J4P"] = section_forces(pts, "J4P", [(pts["J4"], -T[0] * e45, 0.0)])  # free end side
        out["J4J5"] = np.array([0.0, 0.0, T[0], 0.0])
        out["J5J6"] = np.array([0.0, 0.0, T[1], 0.0])
        return out
    if tuple(act) == ("J1", "J2", "J6"):
        # Frozen J1, J2, J6; pins at J3, J4, J5.  Left limb = L-shaped cantilever
        # clamped at J1 ending in pin J3; bar J4J5 = two-force member; J5J6 =
        # cantilever clamped at J6 ending in pin J5; platform J3-P-J4 = beam on
        # pins J3, J4 with the load at P.  Platform equilibrium, unknowns:
        # R3 (force of the left limb on the platform at J3), f (tension of bar
        # J4J5; force on the platform at J4 = f*u, u = unit(J5 - J4)).
        u = (pts["J5"] - pts["J4"]) / L45
        r3 = pts["J3"] - P
        r4 = pts["J4"] - P
        Aeq = np.array([[1.0, 0.0, u[0]],
                        [0.0, 1.0, u[1]],
                        [-r3[1], r3[0], cross2(r4, u)]])
        sol = np.linalg.solve(Aeq, -np.array([Fx, Fy, Mz]))
        R3, f = sol[:2], sol[2]
        out["J1J2"] = section_forces(pts, "J1J2", [(pts["J3"], -R3, 0.0)])
        out["J2J3"] = section_forces(pts, "J2J3", [(pts["J3"], -R3, 0.0)])
        out["J3P"] = section_forces(pts, "J3P", [(pts["J3"], R3, 0.0)])
        out["J4P"] = section_forces(pts, "J4P", [(pts["J4"], f * u, 0.0)])
        out["J4J5"] = np.array([0.0, 0.0, f, 0.0])           # pure axial, tension +
        out["J5J6"] = section_forces(pts, "J5J6", [(pts["J5"], -f * u, 0.0)])
        return out
    raise NotImplementedError(act)


def seg_len(pts, s):
    a, b = seg_ends(pts, s)
    return np.linalg.norm(pts[b] - pts[a])


def unit_load_compliance(pts, act):
    """Returns per-segment 3x3 integrals (bending int M_i M_j ds [m^3 per unit
    loads], axial int N_i N_j ds, shear int V_i V_j ds) for loads [Mz, Fx, Fy]."""
    forces = [unit_load_forces(pts, act, w) for w in np.eye(3)]
    res = {}
    for s in SEGS:
        L = seg_len(pts, s)
        Bm = np.zeros((3, 3))
        Ax = np.zeros((3, 3))
        Sh = np.zeros((3, 3))
        for i in range(3):
            for j in range(3):
                fi, fj = forces[i][s], forces[j][s]
                # M linear along the segment (no load inside a segment)
                Bm[i, j] = L / 6 * (2 * fi[0] * fj[0] + fi[0] * fj[1] + fi[1] * fj[0] + 2 * fi[1] * fj[1])
                Ax[i, j] = L * fi[2] * fj[2]
                Sh[i, j] = L * fi[3] * fj[3]
        res[s] = (Bm, Ax, Sh)
    return res


def compliance_from_integrals(res, terms="bending"):
    """Compliance times E*I_z (so that K_S comes out in units of E*I_z)."""
    C = np.zeros((3, 3))
    for s, (Bm, Ax, Sh) in res.items():
        C += Bm
        if terms == "all":
            C += Ax * I_SEC / A_SEC + Sh * K_SHEAR * E_MOD * I_SEC / (G_MOD * A_SEC)
    return C


# --------------------------------------------------------------------------
# 5. Tiny 2-D frame stiffness method (independent of the equilibrium above)
# --------------------------------------------------------------------------
def beam_k_local(L, EA, EI, phi_s):
    """Two-node plane beam, dofs (u1, v1, th1, u2, v2, th2); phi_s = 12 EI k/(G A L^2)
    (phi_s = 0: Euler-Bernoulli; > 0: Timoshenko, exact for end-loaded members)."""
    k = np.zeros((6, 6))
    a = EA / L
    k[np.ix_([0, 3], [0, 3])] = a * np.array([[1, -1], [-1, 1]])
    c = EI / (L ** 3 * (1 + phi_s))
    kb = c * np.array([[12, 6 * L, -12, 6 * L],
                       [6 * L, (4 + phi_s) * L * L, -6 * L, (2 - phi_s) * L * L],
                       [-12, -6 * L, 12, -6 * L],
                       [6 * L, (2 - phi_s) * L * L, -6 * L, (4 + phi_s) * L * L]])
    idx = [1, 2, 4, 5]
    k[np.ix_(idx, idx)] = kb
    return k


def condense(k, released):
    """Static condensation of released end rotations (hinges): rows/cols zeroed."""
    if not released:
        return k
    keep = [i for i in range(6) if i not in released]
    kk = k[np.ix_(keep, keep)]
    kr = k[np.ix_(keep, released)]
    rr = k[np.ix_(released, released)]
    kc = np.zeros((6, 6))
    kc[np.ix_(keep, keep)] = kk - kr @ np.linalg.solve(rr, kr.T)
    return kc


def fem_compliance(pts, act, terms="bending"):
    """Compliance at P ([phi, x, y] order) times E*I_z.
    Nodes J1 J2 J3 P J4 J5 J6; elements J1J2 J2J3 J3P PJ4 J4J5 J5J6.
    A frozen (actuated) joint is a rigid connection, a passive joint is a pin:
    J1, J6 pinned -> the element end at the ground is released; an internal pin
    between elements e1 -> e2 releases the end of e2 at that node."""
    nodes = ["J1", "J2", "J3", "P", "J4", "J5", "J6"]
    elems = [("J1", "J2"), ("J2", "J3"), ("J3", "P"), ("P", "J4"), ("J4", "J5"), ("J5", "J6")]
    # which element end carries the release of each passive joint
    release_of = {"J1": (0, 0), "J2": (1, 0), "J3": (2, 0), "J4": (4, 0), "J5": (4, 1), "J6": (5, 1)}
    EI = E_MOD * I_SEC
    if terms == "bending":
        EA, phi_fac = EI * 1e9, 0.0      # axially rigid, shear rigid
    elif terms == "bending+axial":
        EA, phi_fac = E_MOD * A_SEC, 0.0
    else:
        EA, phi_fac = E_MOD * A_SEC, 12 * EI * K_SHEAR / (G_MOD * A_SEC)
    rel = {i: [] for i in range(len(elems))}
    for j in JOINTS:
        if j not in act:
            ei, end = release_of[j]
            rel[ei].append(2 if end == 0 else 5)
    ndof = 3 * len(nodes)
    K = np.zeros((ndof, ndof))
    for ei, (a, b) in enumerate(elems):
        A, B = pts[a], pts[b]
        L = np.linalg.norm(B - A)
        c, s = (B - A) / L
        T3 = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
        T = np.zeros((6, 6))
        T[:3, :3] = T3
        T[3:, 3:] = T3
        kl = condense(beam_k_local(L, EA, EI, phi_fac / L ** 2), rel[ei])
        kg = T.T @ kl @ T
        dofs = [3 * nodes.index(a) + i for i in range(3)] + [3 * nodes.index(b) + i for i in range(3)]
        K[np.ix_(dofs, dofs)] += kg
    fixed = [0, 1, 2, 18, 19, 20]  # ground nodes J1 and J6 (their rotation: see releases)
    free = [i for i in range(ndof) if i not in fixed]
    Kf = K[np.ix_(free, free)]
    iP = 3 * nodes.index("P")
    C = np.zeros((3, 3))
    for c_, d in enumerate([iP + 2, iP, iP + 1]):  # loads: Mz, Fx, Fy
        f = np.zeros(ndof)
        f[d] = 1.0
        u = np.zeros(ndof)
        u[free] = np.linalg.solve(Kf, f[free])
        C[:, c_] = [u[iP + 2], u[iP], u[iP + 1]]
    return C * EI


def fem_compliance_springs(pts, act, k_act, rigid_links=False):
    """Frame model of the whole manipulator: every joint gets its own rotation
    dof on the element side; a passive joint is a free pin, an actuated joint
    is a rotational spring k_act (N m/rad) between the element end and the node
    (or the ground for J1, J6).  Bending + axially rigid links (EA = 1e6 EI),
    EI = E_MOD*I_SEC; rigid_links=True multiplies EI by 1e6 (EA = 1e6 EI).
    Returns the compliance at P in [phi, x, y] order (not normalised)."""
    nodes = ["J1", "J2", "J3", "P", "J4", "J5", "J6"]
    elems = [("J1", "J2"), ("J2", "J3"), ("J3", "P"), ("P", "J4"), ("J4", "J5"), ("J5", "J6")]
    joint_end = {"J1": (0, 0), "J2": (1, 0), "J3": (2, 0), "J4": (4, 0), "J5": (4, 1), "J6": (5, 1)}
    EI = E_MOD * I_SEC * (1e6 if rigid_links else 1.0)
    EA = EI * 1e6
    ndof = 3 * len(nodes) + len(JOINTS)   # one private rotation dof per joint
    K = np.zeros((ndof, ndof))
    priv = {j: 3 * len(nodes) + k for k, j in enumerate(JOINTS)}
    for ei, (a, b) in enumerate(elems):
        A, B = pts[a], pts[b]
        L = np.linalg.norm(B - A)
        c, s_ = (B - A) / L
        T3 = np.array([[c, s_, 0], [-s_, c, 0], [0, 0, 1]])
        T = np.zeros((6, 6))
        T[:3, :3] = T3
        T[3:, 3:] = T3
        kg = T.T @ beam_k_local(L, EA, EI, 0.0) @ T
        dofs = [3 * nodes.index(a) + i for i in range(3)] + [3 * nodes.index(b) + i for i in range(3)]
        for j, (ej, end) in joint_end.items():
            if ej == ei:
                dofs[2 if end == 0 else 5] = priv[j]
        K[np.ix_(dofs, dofs)] += kg
    for j in act:
        node_rot = 3 * nodes.index(j) + 2
        pr = priv[j]
        K[np.ix_([pr, node_rot], [pr, node_rot])] += k_act * np.array([[1, -1], [-1, 1]])
    fixed = [0, 1, 2, 18, 19, 20]  # ground translations and ground "rotation" of J1, J6
    free = [i for i in range(ndof) if i not in fixed]
    Kf = K[np.ix_(free, free)]
    iP = 3 * nodes.index("P")
    C = np.zeros((3, 3))
    for c_, d in enumerate([iP + 2, iP, iP + 1]):
        f = np.zeros(ndof)
        f[d] = 1.0
        u = np.zeros(ndof)
        u[free] = np.linalg.solve(Kf, f[free])
        C[:, c_] = [u[iP + 2], u[iP], u[iP + 1]]
    return C
