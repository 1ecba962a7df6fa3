#!/usr/bin/python3
"""Generate the beamfea models of the Pashkevich, Klimchik & Chablat (2010) chain U_p R_a R_a S_p.

Source: A. Pashkevich, A. Klimchik, D. Chablat, "Enhanced stiffness modeling of serial
manipulators with passive joints", Advances in Robot Manipulators, InTech 2010, eq. 33
(text: ../../../shared/papers/000_9fcd638e60a85b77.txt); readings of the garbled equations in
docs/notes/pashkevich-reference.md.

Units: link length L = 1, reference stiffness K_theta = E*I_z/L = 1 (so E = 1, I_z = 1);
forces come out in K_theta/L, stiffness in K_theta/L^2.

For every spring model (A, B, C) and posture (S, Pi, Z) two models are written:

  lumped  (VJM)  rigid links + 6-D "virtual_spring" joints (eq. 1, T_3D = Tx Ty Tz Rx Ry Rz),
                 n springs per link, each at the end of its segment (the cantilever stiffness
                 of that segment, eq. 39, by "stiffness_from_beam"); model A instead has rigid
                 links and revolute actuator springs K_theta.
  beam           the same links as N Euler-Bernoulli (co-rotational) beam elements each, of the
                 material and section whose cantilever stiffness is the lumped spring.

Mapping lumped <-> beam (this is what makes them "the same links"):
  model B  eq. 36/37 with K_theta = E I_z / L and I_z/A = b^2/12, b = 0.05 L (in-plane):
           E = 1, I_z = 1, A = 12/b^2 = 4800. "Planar" springs: the out-of-plane bending and
           the torsion are made 100x stiffer (I_y = 100, G J = 100 E I_z), so the in-plane
           response is exactly that of the planar model and out-of-plane buckling is pushed
           100x above the in-plane loads.
  model C  eq. 39 with the a x b rectangle, a = 0.02 L along z (thin), b = 0.05 L along y:
           I_y/I_z = k_I = (a/b)^2 = 0.16, nu = 0.3 (G = E/2.6), Roark's torsion constant
           J = a^3 b [1/3 - 0.21 (a/b)(1 - (a/b)^4/12)] (the paper gives neither G nor J).
  model A  lumped: rigid links, revolute actuator springs K_theta about z.
           beam: the same actuator springs with very stiff beam links (E I_z = 1000 K_theta L,
           I_y = 1000, A = 1e6, G J = 1000): the beam model tends to model A as the links
           stiffen.

Boundary conditions (eq. 33): base node B fixed; universal joint R_u = Rz(q1) Ry(q2) between B
and the first link; spherical joint between the chain tip T and the end node E; E is held on
the x axis (uy, uz fixed; its rotations fixed too, which with the spherical joint leaves the tip
free to rotate) and pushed toward the base: a unit load (-1, 0, 0) at E whose load factor is
the compressive force P, followed by arc length (the engine switches branches only under arc-length
control) until E's ux reaches -delta_max. With y and z held at E, the (delta, P) curve is the
displacement-controlled curve of the paper; only the stability of a falling branch (dP/ddelta < 0)
differs: stable under displacement control, unstable under this load.

Run: /usr/bin/python3 examples/05_pashkevich_chain/generate.py [--out DIR]
"""
import argparse
import json
import math
import os

L = 1.0
B_THIN, B_WIDE = 0.02, 0.05     # a (along z) and b (along y), in units of L

POSTURES = {
    # actuated angles q_a1, q_a2 and the initial universal-joint angle q1 (end on the x axis):
    # sin q + sin(q + qa1) + sin(q + qa1 + qa2) = 0 (reference note, section 2)
    "S": (0.0, 0.0, 0.0),
    "Pi": (-30.0, -30.0, 30.0),
    "Z": (-30.0, 30.0, math.degrees(math.atan(0.5 / (2.0 + math.cos(math.radians(30.0)))))),
}


def roark_J(a, b):
    """Saint-Venant torsion constant of an a x b rectangle, a <= b (Roark, Table 10.7 case 4)."""
    r = a / b
    return b * a ** 3 * (1.0 / 3.0 - 0.21 * r * (1.0 - r ** 4 / 12.0))


def material_section(model):
    """Material and section (E = 1, I_z = 1 so that K_theta = E I_z / L = 1)."""
    Iz = 1.0
    A = 12.0 * Iz / B_WIDE ** 2
    if model == "A":
        return {"id": "steel", "E": 1.0, "G": 1.0}, {"id": "link", "A": 1e6, "Iz": 1e3, "Iy": 1e3, "J": 1e3}
    if model == "B":
        return {"id": "mat", "E": 1.0, "G": 1.0 / 2.6}, {"id": "link", "A": A, "Iz": Iz, "Iy": 100.0 * Iz,
                                                         "J": 100.0 * Iz * 2.6}
    kI = (B_THIN / B_WIDE) ** 2
    Iz_real = B_THIN * B_WIDE ** 3 / 12.0
    return ({"id": "mat", "E": 1.0, "nu": 0.3},
            {"id": "link", "A": A, "Iz": Iz, "Iy": kI * Iz, "J": roark_J(B_THIN, B_WIDE) / Iz_real * Iz})


def link_directions(posture):
    qa1, qa2, q1 = (math.radians(v) for v in POSTURES[posture])
    return [q1, q1 + qa1, q1 + qa1 + qa2]


def end_x(posture):
    return sum(L * math.cos(a) for a in link_directions(posture))


def r(v):
    return [round(c, 15) for c in v]


def build(model, posture, kind, n, delta_max=1.0, ds=2e-4, ds_max=0.01):
    """kind: 'lumped' (n virtual springs per link) or 'beam' (n elements per link)."""
    mat, sec = material_section(model)
    alphas = link_directions(posture)
    nodes, elements, joints = [], [], []
    nodes.append({"id": "B", "xyz": [0.0, 0.0, 0.0]})
    nodes.append({"id": "P0", "xyz": [0.0, 0.0, 0.0]})
    q1 = alphas[0]
    joints.append({"id": "U", "type": "universal", "nodes": ["B", "P0"],
                   "axes": [[0, 0, 1], r([-math.sin(q1), math.cos(q1), 0.0])],
                   "_comment": "R_u = Rz(q1) Ry(q2): the second axis is the y axis turned by q1"})
    x = [0.0, 0.0]
    start = "P0"
    for i, a in enumerate(alphas, start=1):
        d = [math.cos(a), math.sin(a), 0.0]
        frame = [r(d), r([-d[1], d[0], 0.0]), [0, 0, 1]]
        if kind == "beam":
            x = [x[0] + L * d[0], x[1] + L * d[1]]
            end = f"N{i}"
            nodes.append({"id": end, "xyz": r([x[0], x[1], 0.0])})
            elements.append({"id": f"link{i}", "type": "beam", "nodes": [start, end], "material": mat["id"],
                             "section": sec["id"], "orientation": [0, 0, 1], "divisions": n})
            start = end
        elif model == "A":
            x = [x[0] + L * d[0], x[1] + L * d[1]]
            end = f"N{i}"
            nodes.append({"id": end, "xyz": r([x[0], x[1], 0.0])})
            elements.append({"id": f"link{i}", "type": "rigid", "nodes": [start, end]})
            start = end
        else:
            for k in range(1, n + 1):
                x = [x[0] + L / n * d[0], x[1] + L / n * d[1]]
                a_id, b_id = f"L{i}_{k}", f"L{i}_{k}s"
                nodes.append({"id": a_id, "xyz": r([x[0], x[1], 0.0])})
                nodes.append({"id": b_id, "xyz": r([x[0], x[1], 0.0])})
                elements.append({"id": f"link{i}_{k}", "type": "rigid", "nodes": [start, a_id]})
                # The segment's spring sits at its end, in the segment's frame (x along the link,
                # z the thin direction): T_s(theta) of eq. 33, the cantilever tip stiffness eq. 39.
                joints.append({"id": f"spring{i}_{k}", "type": "virtual_spring", "nodes": [a_id, b_id], "axes": frame,
                               "stiffness_from_beam": {"material": mat["id"], "section": sec["id"], "length": L / n}})
                start = b_id
        if i < 3 and model == "A":
            # Actuated joint R_a with its actuator spring K_theta (model A, eq. 34).
            nxt = f"N{i}a"
            nodes.append({"id": nxt, "xyz": r([x[0], x[1], 0.0])})
            joints.append({"id": f"act{i}", "type": "revolute", "nodes": [start, nxt], "axes": [[0, 0, 1]],
                           "stiffness": [1.0]})
            start = nxt
        # models B, C: actuators rigid, the next link starts where this one ends.
    nodes.append({"id": "E", "xyz": r([x[0], x[1], 0.0])})
    joints.append({"id": "S", "type": "spherical", "nodes": [start, "E"]})
    # Arc length (Crisfield) with automatic branch switching: the engine switches onto the stable
    # branch at a bifurcation only under arc-length control. The end is loaded by the unit load
    # (-1, 0, 0), so the load factor is the compressive force P and the (delta, P) curve is the
    # displacement-controlled curve of the paper; the path stops when E has moved delta_max.
    path = {"id": "path", "type": "path", "track": ["E"], "max_steps": 2000,
            "control": {"arc_length": ds, "min": 1e-7, "max": ds_max},
            "stop": {"node": "E", "dof": "ux", "beyond": -delta_max},
            "branch_switch": True}
    doc = {
        "title": f"Pashkevich et al. (2010) chain U_p R_a R_a S_p, model {model}, posture {posture}, "
                 f"{kind} ({n} {'springs' if kind == 'lumped' else 'elements'} per link)",
        "units": "L = 1, K_theta = 1",
        "nodes": nodes,
        "materials": [mat],
        "sections": [sec],
        "elements": elements,
        "joints": joints,
        "supports": [{"node": "B", "fix": "all"}, {"node": "E", "fix": ["uy", "uz", "rx", "ry", "rz"]}],
        "loads": [{"node": "E", "force": [-1.0, 0.0, 0.0]}],
        "analyses": [path],
    }
    if posture == "S":
        doc["analyses"].append({"id": "buckling", "type": "buckling", "modes": 2})
    return doc


def write(doc, path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


# Verified reference values (docs/notes/pashkevich-reference.md, sections 6-8; the printed values of
# Tables 2-4 beside them). Critical force in K_theta/L; stiffness coefficients k = dP/ddelta.
REFERENCE = {
    ("A", "S"): {"critical_force": 1.0, "buckling_load": 1.0, "unloaded": math.inf, "near_after": 1 / 6, "large": 0.2636, "P_at_L": 1.2092},
    ("A", "Pi"): {"critical_force": None, "unloaded": 2.0, "large": 0.4246, "P_at_L": 0.7226},
    ("A", "Z"): {"critical_force": 1.0330, "unloaded": 10 + 4 * math.sqrt(3), "near_before": 5.429,
                 "near_after": 0.2029, "large": 0.3919, "P_at_L": 1.2821},
    ("B", "S"): {"critical_force": math.sqrt(21) - 3, "buckling_load": math.sqrt(21) - 3, "unloaded": 1600.0, "near_after": 0.2384, "large": 0.2820,
                 "P_at_L": 1.8485},
    ("B", "Pi"): {"critical_force": None, "unloaded": 2.3970, "large": 0.6375, "P_at_L": 1.0434},
    ("B", "Z"): {"critical_force": 1.545, "unloaded": 33.195, "large": 0.0744, "P_at_L": 1.9191,
                 "_note": "knee (imperfect bifurcation), not a true critical point"},
    ("C", "S"): {"critical_force": 0.16 * (math.sqrt(21) - 3), "buckling_load": 0.16 * (math.sqrt(21) - 3), "unloaded": 1600.0, "near_after": 0.03816,
                 "large": 0.04518, "P_at_L": 0.2957},
    ("C", "Pi"): {"critical_force": 0.2720, "unloaded": 2.3970, "near_before": 1.576, "near_after": 0.0326,
                  "large": -0.047, "P_at_L": 0.2679},
    ("C", "Z"): {"critical_force": 0.2679, "unloaded": 33.195, "near_before": 32.97, "near_after": 0.0502,
                 "large": -0.064, "P_at_L": 0.3009},
}
# Curve samples (delta/L, P) of the reference note, sections 6-7 (lumped model, 1 spring per link).
CURVES = {
    ("A", "S"): [(0.02, 1.0033), (0.10, 1.0170), (0.20, 1.0347), (0.40, 1.0725), (1.00, 1.2092)],
    ("A", "Pi"): [(0.02, 0.0380), (0.10, 0.1604), (0.20, 0.2716), (0.40, 0.4268), (1.00, 0.7226)],
    ("A", "Z"): [(0.02, 0.2923), (0.10, 0.9719), (0.20, 1.0520), (0.40, 1.0976), (1.00, 1.2821)],
    ("B", "S"): [(0.02, 1.5878), (0.10, 1.6072), (0.20, 1.6319), (0.40, 1.6832), (1.00, 1.8485)],
    ("B", "Pi"): [(0.02, 0.0463), (0.10, 0.2043), (0.20, 0.3591), (0.40, 0.5893), (1.00, 1.0434)],
    ("B", "Z"): [(0.02, 0.6538), (0.10, 1.6241), (0.20, 1.6708), (0.40, 1.7513), (1.00, 1.9191)],
    ("C", "S"): [(0.02, 0.2540), (0.10, 0.2571), (0.20, 0.2610), (0.40, 0.2693), (0.60, 0.2778), (1.00, 0.2957)],
    ("C", "Pi"): [(0.02, 0.0463), (0.10, 0.2043), (0.20, 0.2739), (0.40, 0.2794), (0.60, 0.2820), (1.00, 0.2679)],
    ("C", "Z"): [(0.02, 0.2685), (0.10, 0.2725), (0.20, 0.2777), (0.40, 0.2882), (0.60, 0.2982), (1.00, 0.3009)],
}
PRINTED = {  # Tables 2-4 of the paper as printed: F_cr, unloaded, F<F_cr, F>F_cr, delta ~ L
    ("A", "S"): {"critical_force": 1.0, "unloaded": math.inf, "near_after": 0.20, "large": 0.22},
    ("A", "Pi"): {"critical_force": None, "unloaded": 1.78, "large": 0.43},
    ("A", "Z"): {"critical_force": 1.03, "unloaded": 16.7, "near_before": 5.50, "near_after": 0.20, "large": 0.39},
    ("B", "S"): {"critical_force": 1.00, "unloaded": 2500.0, "near_after": 0.20, "large": 0.22},
    ("B", "Pi"): {"critical_force": None, "unloaded": 5.31, "large": 0.34},
    ("B", "Z"): {"critical_force": 1.07, "unloaded": 100.0, "near_before": 0.13, "near_after": 0.13, "large": 0.16},
    ("C", "S"): {"critical_force": 0.16, "unloaded": 2500.0, "near_after": 0.023, "large": 0.029},
    ("C", "Pi"): {"critical_force": 0.20, "unloaded": 1.70, "near_before": 1.03, "near_after": 0.043, "large": 0.13},
    ("C", "Z"): {"critical_force": 0.17, "unloaded": 7.52, "near_before": 5.88, "near_after": 0.027, "large": 0.035},
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--out", default=os.path.join(here, "models"))
    ap.add_argument("--beam-elements", type=int, default=8, help="N elements per link of the beam models")
    ap.add_argument("--convergence", metavar="DIR", default=None,
                    help="also write the mesh / spring-count series (N, n = 1, 2, 4, 8, 16) into DIR")
    args = ap.parse_args()
    pairs = []
    for model in "ABC":
        for posture in POSTURES:
            lumped = f"{model}_{posture}_lumped.json"
            beam = f"{model}_{posture}_beam.json"
            write(build(model, posture, "lumped", 1), os.path.join(args.out, lumped))
            write(build(model, posture, "beam", args.beam_elements), os.path.join(args.out, beam))
            pairs.append({
                "name": f"model {model}, {posture} posture",
                "id": f"{model}_{posture}",
                "lumped": {"file": f"models/{lumped}", "label": "lumped (VJM)"},
                "beam": {"file": f"models/{beam}", "label": f"beam ({args.beam_elements} el./link)"},
                "paper": PRINTED[(model, posture)],
                "reference": {k: v for k, v in REFERENCE[(model, posture)].items() if not k.startswith("_")},
                "reference_curve": {"label": "reference VJM (note)", "points": CURVES[(model, posture)]},
            })
            if args.convergence and model in "BC":
                for n in (1, 2, 4, 8, 16):
                    write(build(model, posture, "beam", n), os.path.join(args.convergence, f"{model}_{posture}_beam_N{n}.json"))
                    write(build(model, posture, "lumped", n),
                          os.path.join(args.convergence, f"{model}_{posture}_lumped_n{n}.json"))
    spec = {
        "title": "Pashkevich, Klimchik & Chablat (2010), chain U_p R_a R_a S_p: lumped (VJM) vs beam",
        "path_analysis": "path",
        "force": {"from": "load_factor", "scale": 1.0, "label": "P [K_theta/L]"},
        "deflection": {"node": "E", "dof": "ux", "scale": -1.0, "label": "delta [L]"},
        "stiffness_node": "E",
        "quantities": ["critical_force", "buckling_load", "unloaded", "near_before", "near_after", "large", "P_at_L"],
        "large_deflection": 1.0,
        "near_offset": 1e-3,
        "pairs": pairs,
    }
    with open(os.path.join(here, "comparison_spec.json"), "w") as f:
        json.dump(spec, f, indent=1)
        f.write("\n")
    print(f"wrote {len(pairs)} pairs of models to {args.out} and comparison_spec.json")


if __name__ == "__main__":
    main()
