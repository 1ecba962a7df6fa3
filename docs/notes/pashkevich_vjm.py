"""The machinery of pashkevich_reference.py: kinematics of a serial chain of
elementary joints, VJM statics (equilibrium, stability, stiffness), the
U_p R_a R_a S_p chain with its spring models A, B, C, and path following to the
critical force. Formulation and readings: docs/notes/pashkevich-reference.md.
Needs numpy + scipy.
"""
import numpy as np
from scipy.optimize import brentq
from scipy.linalg import block_diag, null_space

D2R = np.pi / 180

# =========================================================================
# 1. Kinematics of a serial chain of elementary joints (eqs. 1, 2, 33)
# =========================================================================
def rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    R = np.eye(4)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R[i, i] = c; R[i, j] = -s; R[j, i] = s; R[j, j] = c
    return R


def tra(axis, d):
    T = np.eye(4); T[axis, 3] = d
    return T


class Chain:
    """items: ('C', 4x4) constant transform, or (kind, local_axis, var, offset)
    with kind 'R' (rotation) / 'P' (translation); the joint value is
    z[var] + offset (var None: constant joint, e.g. an actuated angle).
    Output t = end-point position, rows `rows` (x,y) or (x,y,z).
    z = [q (nq passive coordinates), theta (virtual springs)]."""

    def __init__(self, items, nvar, rows, nq, K):
        self.items, self.n, self.rows, self.nq, self.K = items, nvar, list(rows), nq, K

    def fk(self, z):
        T = np.eye(4); axes = []
        for it in self.items:
            if it[0] == 'C':
                T = T @ it[1]; continue
            kind, ax, var, off = it
            val = off + (z[var] if var is not None else 0.0)
            if var is not None:
                axes.append((var, kind, T[:3, ax].copy(), T[:3, 3].copy()))
            T = T @ (rot(ax, val) if kind == 'R' else tra(ax, val))
        return T, axes

    def pos(self, z):
        return self.fk(z)[0][:3, 3][self.rows]

    def derivs(self, z):
        """p, Jacobian J = dp/dz, Hessians H[k] = d2 p_k/dz2 (analytic, screw form):
        dp/dz_j = w_j x (p - o_j) (rotation) or w_j (translation);
        d2p/dz_j dz_k (j not after k) = w_j x dp/dz_k if j is a rotation, else 0."""
        T, axes = self.fk(z)
        p = T[:3, 3]
        J3 = np.zeros((3, self.n)); order = []
        for var, kind, w, o in axes:
            J3[:, var] = np.cross(w, p - o) if kind == 'R' else w
            order.append((var, kind, w))
        H3 = np.zeros((3, self.n, self.n))
        for a, (vj, kj, wj) in enumerate(order):
            if kj != 'R':
                continue
            for b in range(a, len(order)):
                vk = order[b][0]
                h = np.cross(wj, J3[:, vk])
                H3[:, vj, vk] = h; H3[:, vk, vj] = h
        return p[self.rows], J3[self.rows], H3[self.rows]


# =========================================================================
# 2. VJM statics: equilibrium (5-11), stability (12-23), stiffness (24-32)
# =========================================================================
class VJM:
    """Displacement control: the end point is prescribed (t = target), the
    springs' energy 1/2 theta^T K theta is stationary on {g(q,theta) = t}.
    The Lagrange multiplier is the external force F on the end point
    (eq. 7: J_theta^T F = K theta, J_q^T F = 0)."""

    def __init__(self, chain):
        self.c = chain
        n, nq = chain.n, chain.nq
        self.Kfull = np.zeros((n, n)); self.Kfull[nq:, nq:] = chain.K

    def energy(self, z):
        return 0.5 * z @ self.Kfull @ z

    def W(self, z, F):
        """blockdiag(0, K_theta) - H^F, H^F = d2(F^T g)/dz2 (eq. 16)."""
        p, J, H = self.c.derivs(z)
        return p, J, H, self.Kfull - np.tensordot(F, H, axes=(0, 0))

    def solve(self, z, F, target, tol=1e-12, maxit=60):
        """Full Newton-Raphson on the equilibrium + kinematic equations (the
        'full-scale Newton' the paper mentions after eq. 11)."""
        n, m = self.c.n, len(target)
        for _ in range(maxit):
            p, J, H, W = self.W(z, F)
            r1 = self.Kfull @ z - J.T @ F
            r2 = p - target
            if np.linalg.norm(r1) < tol and np.linalg.norm(r2) < tol:
                return z, F, True
            A = np.block([[W, -J.T], [J, np.zeros((m, m))]])
            try:
                d = np.linalg.solve(A, -np.concatenate([r1, r2]))
            except np.linalg.LinAlgError:
                d = np.linalg.lstsq(A, -np.concatenate([r1, r2]), rcond=None)[0]
            z = z + d[:n]; F = F + d[n:]
            if not np.all(np.isfinite(z)):
                return z, F, False
        return z, F, False

    def iterate_eq11(self, z, target, iters=200):
        """The paper's own fixed-point scheme, eq. (11) (for cross-checking)."""
        nq = self.c.nq; Kinv = np.linalg.inv(self.c.K)
        m = len(target)
        for _ in range(iters):
            p, J, _ = self.c.derivs(z)
            Jq, Jt = J[:, :nq], J[:, nq:]
            q, th = z[:nq], z[nq:]
            A = np.block([[Jt @ Kinv @ Jt.T, Jq], [Jq.T, np.zeros((nq, nq))]])
            rhs = np.concatenate([target - p + Jq @ q + Jt @ th, np.zeros(nq)])
            sol = np.linalg.lstsq(A, rhs, rcond=None)[0]
            F = sol[:m]; q = sol[m:]
            z = np.concatenate([q, Kinv @ Jt.T @ F])
        return z, F

    def reduced_hessian(self, z, F):
        """eqs. (19)-(22): null space of [J_theta J_q] by SVD; the equilibrium
        is stable iff V0^T (blockdiag(0,K) - H^F) V0 is positive definite."""
        p, J, H, W = self.W(z, F)
        Z = null_space(J, rcond=1e-10)
        ev, evec = np.linalg.eigh(Z.T @ W @ Z)
        return ev, Z @ evec

    def minimise(self, z, target, maxit=200, tol=1e-11):
        """Energy minimisation on the constraint manifold (projected Newton
        with negative-curvature escape) -> a STABLE equilibrium."""
        def project(z):
            for _ in range(50):
                p, J, _ = self.c.derivs(z)
                r = p - target
                if np.linalg.norm(r) < 1e-14:
                    break
                z = z - np.linalg.pinv(J) @ r
            return z
        z = project(z); F = np.zeros(len(target))
        for _ in range(maxit):
            p, J, H = self.c.derivs(z)
            g = self.Kfull @ z
            F = np.linalg.lstsq(J.T, g, rcond=None)[0]
            Z = null_space(J, rcond=1e-10)
            W = self.Kfull - np.tensordot(F, H, axes=(0, 0))
            gr = Z.T @ g; Hr = Z.T @ W @ Z
            ev, V = np.linalg.eigh(Hr)
            if np.linalg.norm(gr) < tol * max(1.0, np.linalg.norm(g)) and ev[0] > 0:
                break
            if np.linalg.norm(gr) < 1e-8 * max(1.0, np.linalg.norm(g)) and ev[0] > 0:
                break                      # close enough: Newton (solve) polishes
            if ev[0] <= 1e-9 * max(1, abs(ev[-1])):
                v = V[:, 0]; dv = v if v @ gr < 0 else -v
                shift = -ev[0] + 1e-3 * max(1.0, abs(ev[-1]))
                d = -np.linalg.solve(Hr + shift * np.eye(len(ev)), gr) + 0.1 * dv
            else:
                d = -np.linalg.solve(Hr, gr)
            E0 = self.energy(z); a = 1.0; accepted = False
            while a > 1e-6:
                zn = project(z + a * (Z @ d))
                if self.energy(zn) < E0 - 1e-15 * max(1.0, E0):
                    accepted = True
                    break
                a *= 0.5
            if not accepted:
                break
            z = zn
        return self.solve(z, F, target)

    def stiffness(self, z, F):
        """eq. (28): [[W, -J^T],[J, 0]] [dz; dF] = [0; dt] -> dF = K_F dt.
        Returns the m x m matrix K_F (inf if the system is singular)."""
        p, J, H, W = self.W(z, F)
        n, m = self.c.n, len(F)
        A = np.block([[W, -J.T], [J, np.zeros((m, m))]])
        if np.linalg.cond(A) > 1e13:
            return np.full((m, m), np.inf)
        return np.linalg.inv(A)[n:, n:]

    def stiffness_eq31(self, z, F):
        """eqs. (30)-(32): theta eliminated with k_theta^F = (K - H_thth)^-1."""
        nq = self.c.nq
        p, J, H = self.c.derivs(z)
        HF = np.tensordot(F, H, axes=(0, 0))
        Jq, Jt = J[:, :nq], J[:, nq:]
        Hqq, Hqt, Htt = HF[:nq, :nq], HF[:nq, nq:], HF[nq:, nq:]
        kF = np.linalg.inv(self.c.K - Htt)
        M = np.block([[Jt @ kF @ Jt.T, Jq + Jt @ kF @ Hqt.T],
                      [Jq.T + Hqt @ kF @ Jt.T, Hqq + Hqt @ kF @ Hqt.T]])
        m = J.shape[0]
        if np.linalg.cond(M) > 1e13:
            return np.full((m, m), np.inf)
        return np.linalg.inv(M)[:m, :m]


# =========================================================================
# 3. The U_p R_a R_a S_p chain, postures, spring models A, B, C
# =========================================================================
POSTURES = {'S': (0.0, 0.0), 'Pi': (-30 * D2R, -30 * D2R), 'Z': (-30 * D2R, 30 * D2R)}
A_SEC, B_SEC = 0.02, 0.05      # cross-section a x b (L = 1); a along z, b along y
NU = 0.3                        # Poisson ratio (not given in the paper)


def torsion_constant(a, b):
    """Rectangle a x b (a <= b), Roark: J = a^3 b [1/3 - 0.21 (a/b)(1 - a^4/(12 b^4))]."""
    return a ** 3 * b * (1 / 3 - 0.21 * (a / b) * (1 - a ** 4 / (12 * b ** 4)))


def base_angle(qa):
    """In-plane base angle q putting the unloaded end point on the x axis."""
    f = lambda q: np.sin(q) + np.sin(q + qa[0]) + np.sin(q + qa[0] + qa[1])
    q = brentq(f, -1.2, 1.2)
    return q, np.cos(q) + np.cos(q + qa[0]) + np.cos(q + qa[0] + qa[1])


def model_A(qa):
    """R_p R_a R_a R_p; springs (K_theta each) in the two actuators; z = [q, th1, th2]."""
    it = [('R', 2, 0, 0.0), ('C', tra(0, 1.0)), ('R', 2, 1, qa[0]), ('C', tra(0, 1.0)),
          ('R', 2, 2, qa[1]), ('C', tra(0, 1.0))]
    return Chain(it, 3, [0, 1], 1, np.eye(2))


def K_link_B(n=1):
    """inverse of eq. (37) for a (sub-)link of length 1/n (K_theta,sub = n K_theta)."""
    l, kt = 1.0 / n, float(n)
    k = np.array([[B_SEC ** 2 / 12, 0, 0], [0, l * l / 3, l / 2], [0, l / 2, 1]]) / kt
    return np.linalg.inv(k)


def model_B(qa, n=1, order='TR'):
    """Planar link springs (theta_x, theta_y, theta_phiz) at the END of each link
    (n springs per link for the lumped-convergence study).  order 'TR':
    T_3D = Tx Ty Rz (eq. 1); 'RT': Rz Tx Ty (reading of eq. 38)."""
    it = [('R', 2, 0, 0.0)]; v = 1
    for i in range(3):
        for s in range(n):
            it.append(('C', tra(0, 1.0 / n)))
            spr = [('P', 0, v, 0.0), ('P', 1, v + 1, 0.0), ('R', 2, v + 2, 0.0)]
            it += spr if order == 'TR' else [spr[2], spr[0], spr[1]]
            v += 3
        if i < 2:
            it.append(('R', 2, None, qa[i]))
    return Chain(it, v, [0, 1], 1, block_diag(*[K_link_B(n)] * (3 * n)))


def compliance_C(n=1, nu=NU, Jt=None):
    """Reconstructed eq. (40) (compliance of a cantilever link, units 1/K_theta,
    K_theta = E I_z / L), for a (sub-)link of length l = 1/n."""
    l, kt = 1.0 / n, float(n)
    Iz = A_SEC * B_SEC ** 3 / 12; Iy = A_SEC ** 3 * B_SEC / 12; A = A_SEC * B_SEC
    kI = Iy / Iz
    Jt = torsion_constant(A_SEC, B_SEC) if Jt is None else Jt
    k = np.zeros((6, 6))
    k[0, 0] = Iz / A                                   # axial      L/(EA)
    k[1, 1] = l * l / 3; k[1, 5] = k[5, 1] = l / 2; k[5, 5] = 1          # y / phi_z
    k[2, 2] = l * l / 3 / kI; k[2, 4] = k[4, 2] = -l / 2 / kI; k[4, 4] = 1 / kI  # z / phi_y
    k[3, 3] = 2 * (1 + nu) * Iz / Jt                   # torsion    L/(GJ)
    return k / kt


def model_C(qa, n=1, ujoint='ZY', **kw):
    """U_p R_a R_a S_p in 3-D: universal joint Rz(q1) Ry(q2) (second axis carried by
    the first), 6-D link springs T_3D = Tx Ty Tz Rx Ry Rz at each link end; the
    spherical joint only frees the end orientation -> output = end position."""
    it = ([('R', 2, 0, 0.0), ('R', 1, 1, 0.0)] if ujoint == 'ZY'
          else [('R', 1, 1, 0.0), ('R', 2, 0, 0.0)])
    v = 2
    for i in range(3):
        for s in range(n):
            it.append(('C', tra(0, 1.0 / n)))
            it += [('P', 0, v, 0.0), ('P', 1, v + 1, 0.0), ('P', 2, v + 2, 0.0),
                   ('R', 0, v + 3, 0.0), ('R', 1, v + 4, 0.0), ('R', 2, v + 5, 0.0)]
            v += 6
        if i < 2:
            it.append(('R', 2, None, qa[i]))
    K = np.linalg.inv(compliance_C(n, **kw))
    return Chain(it, v, [0, 1, 2], 2, block_diag(*[K] * (3 * n)))


MODELS = {'A': model_A, 'B': model_B, 'C': model_C}


def setup(mk, post, **kw):
    qa = POSTURES[post]
    ch = MODELS[mk](qa, **kw)
    vj = VJM(ch)
    q0, X0 = base_angle(qa)
    z0 = np.zeros(ch.n); z0[0] = q0
    return vj, z0, X0


def target(vj, X0, d):
    t = np.zeros(len(vj.c.rows)); t[0] = X0 - d
    return t


# =========================================================================
# 4. Path following, critical force, stiffness coefficients
# =========================================================================
def stable_at(vj, z, F, tgt, perturb=1e-3):
    """Stable equilibrium near (z, F) at target tgt (disturb + minimise, cf. the
    random noise of section 3.1); returns the lowest-energy stable one found."""
    best = None
    zn, Fn, ok = vj.solve(z.copy(), F.copy(), tgt)
    if ok and vj.reduced_hessian(zn, Fn)[0][0] > 0:
        best = (zn, Fn)
    ev, V = vj.reduced_hessian(zn if ok else z, Fn if ok else F)
    for k in range(6):
        s = perturb * (1 + k) * (1 if k % 2 == 0 else -1)
        zz, FF, ok2 = vj.minimise((zn if ok else z) + s * V[:, 0], tgt)
        if ok2 and vj.reduced_hessian(zz, FF)[0][0] > 0:
            if best is None or vj.energy(zz) < vj.energy(best[0]) - 1e-13:
                best = (zz, FF)
    return best


def follow(vj, z0, X0, deltas):
    """Stable branch under displacement control; returns list of records."""
    z = z0.copy(); F = np.zeros(len(vj.c.rows)); out = []; zprev = None
    for d in deltas:
        tgt = target(vj, X0, d)
        zp = z if zprev is None else 2 * z - zprev
        zn, Fn, ok = vj.solve(zp.copy(), F.copy(), tgt)
        if not ok or vj.reduced_hessian(zn, Fn)[0][0] <= 0:
            r = stable_at(vj, z, F, tgt)
            if r is None:
                raise RuntimeError('no stable equilibrium at delta=%g' % d)
            zn, Fn = r; zprev = None
        else:
            zprev = z
        z, F = zn, Fn
        out.append(dict(d=d, P=-F[0], E=vj.energy(z), z=z.copy(), F=F.copy(),
                        k=vj.stiffness(z, F)[0, 0], ev=vj.reduced_hessian(z, F)[0][0]))
    return out


def critical(vj, z0, X0, dmax=0.4, h=0.005):
    """Continue the initial branch (Newton, no branch switching) and classify:
    'bifurcation': the smallest eigenvalue of the reduced Hessian (eq. 22)
                   crosses zero (bisection on delta to 1e-9);
    'fold'       : the branch turns back in delta (Newton fails, ev -> 0);
    'knee'       : no loss of stability, but ev dips below 10 % of its initial
                   value (imperfect bifurcation): reported at the minimum of ev.
    Returns None when none of these happens up to dmax."""
    z = z0.copy(); F = np.zeros(len(vj.c.rows)); d = 0.0
    ev0 = vj.reduced_hessian(z, F)[0][0]
    hist = [(d, ev0, z, F)]
    while d < dmax:
        dn = d + h
        zn, Fn, ok = vj.solve(z.copy(), F.copy(), target(vj, X0, dn))
        if not ok:
            h /= 2
            if h < 1e-8:
                return dict(dcr=d, Pcr=-F[0], k_before=vj.stiffness(z, F)[0, 0], z=z, F=F, kind='fold')
            continue
        evn = vj.reduced_hessian(zn, Fn)[0][0]
        if evn <= 0:
            lo, hi, zl, Fl = d, dn, z, F
            while hi - lo > 1e-9:
                mid = 0.5 * (lo + hi)
                zm, Fm, okm = vj.solve(zl.copy(), Fl.copy(), target(vj, X0, mid))
                if okm and vj.reduced_hessian(zm, Fm)[0][0] > 0:
                    lo, zl, Fl = mid, zm, Fm
                else:
                    hi = mid
            # eq. (28) is singular AT the bifurcation; take the tangent just before it
            db = lo - max(1e-3 * lo, 1e-7)
            zb, Fb, _ = vj.solve(zl.copy(), Fl.copy(), target(vj, X0, db))
            return dict(dcr=lo, Pcr=-Fl[0], k_before=vj.stiffness(zb, Fb)[0, 0], z=zl, F=Fl,
                        kind='bifurcation')
        z, F, d = zn, Fn, dn
        hist.append((d, evn, z, F))
    i = int(np.argmin([x[1] for x in hist]))
    if hist[i][1] < 0.1 * ev0 and 0 < i < len(hist) - 1:
        # refine the minimum of ev with a fine scan
        d0, _, z, F = hist[i - 1]; best = hist[i]
        for dd in np.linspace(d0, hist[i + 1][0], 81)[1:]:
            z, F, ok = vj.solve(z.copy(), F.copy(), target(vj, X0, dd))
            e = vj.reduced_hessian(z, F)[0][0]
            if e < best[1]:
                best = (dd, e, z.copy(), F.copy())
        d, e, z, F = best
        return dict(dcr=d, Pcr=-F[0], k_before=vj.stiffness(z, F)[0, 0], z=z, F=F, kind='knee',
                    ev_min=e, ev0=ev0)
    return None


def linear_buckling_straight(vj, xrow=0):
    """Critical force of the straight (S) chain: smallest P with
    V0^T (K + P H_x) V0 singular (eq. 22 at z = 0, F = (-P, 0, 0))."""
    z = np.zeros(vj.c.n)
    p, J, H = vj.c.derivs(z)
    Z = null_space(J)
    A = Z.T @ vj.Kfull @ Z; B = -Z.T @ H[xrow] @ Z
    w = np.linalg.eigvals(np.linalg.lstsq(A, B, rcond=None)[0]).real
    return 1.0 / w.max()
