"""The off-model scene catalogue: scene ``sid`` is drawn from a generator seeded by it (drones: 1-6 rotors of 2-3
blades, rates equal or 0.5-4 % apart, uniform, tapered, tip-bright or rough blades, tilts, imbalance, bodies;
birds: a body and flapping wing points; clutter and noise only), with its radar (X, K, 77, 94 GHz) and truth.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import echo as fs_  # noqa: E402

C = fs_.C
BANDS = {"X": 9.8e9, "K": 24.0e9, "77": 76.0e9, "94": 94.0e9}


def make_radar(band, B, N, Tr, prf, dwell, n_ch):
    f0 = BANDS[band]
    fs = N / Tr
    Tp = 1.0 / prf
    assert Tp >= Tr * 1.02, (Tp, Tr)
    M = int(round(dwell * prf))
    lam = C / (f0 + B / 2)
    return dict(f0=f0, B=B, N=N, fs=fs, Tp=Tp, M=M, rx_y=np.arange(n_ch) * lam / 2, lam=lam)


def rbin(radar):
    return C / (2 * radar["B"])


def drone_scene(rng, sid, band=None, fam=None):
    band = band or rng.choice(["X", "K", "77", "94"], p=[0.3, 0.3, 0.2, 0.2])
    lam = C / BANDS[band]
    nrot = int(rng.choice([1, 2, 4, 4, 4, 6])) if fam != "single" else 1
    nbl = int(rng.choice([2, 2, 2, 3]))
    r = float(rng.uniform(0.06, 0.18))
    # tip speed 30-90 m/s
    vtip = float(rng.uniform(35, 85))
    frot = vtip / (2 * np.pi * r)
    equal = nrot > 1 and rng.random() < 0.3
    if equal:
        rates = [frot] * nrot
        phases = [float(i * np.pi / (2 * nbl) * (1 + (i % 2) * 0.3)) for i in range(nrot)]
    else:
        spread = rng.uniform(0.005, 0.04)
        rates = list(frot * (1 + spread * np.linspace(-0.5, 0.5, nrot))) if nrot > 1 else [frot]
        rng.shuffle(rates)
        phases = list(rng.uniform(0, 2 * np.pi, nrot))
    beta = float(rng.choice([0.0, 0.0, rng.uniform(0, 20), rng.uniform(20, 45)]))
    tilt = float(rng.uniform(0, 4))
    arm = 0.12 + 0.5 * r
    rotors = []
    for i in range(nrot):
        ang = 2 * np.pi * i / nrot + np.pi / 4
        rotors.append(dict(offset=[arm * np.cos(ang), arm * np.sin(ang), 0.0], rate=float(rates[i]),
                           phase=float(phases[i]), pitch_deg=float(rng.uniform(-tilt, tilt)),
                           roll_deg=float(rng.uniform(-tilt, tilt))))
    profile = str(rng.choice(["uniform", "tapered:0.3", "tapered:0.6", "tipbright", "rough"]))
    gains = list(1 + rng.uniform(-0.15, 0.15, nbl)) if rng.random() < 0.5 else [1.0] * nbl
    # radar
    tip_dop = 2 * 2 * np.pi * max(rates) * r * np.cos(np.deg2rad(beta)) / lam
    if band == "X":
        B = float(rng.choice([20e6, 50e6, 150e6]))
    elif band == "K":
        B = float(rng.choice([100e6, 250e6]))
    elif band == "77":
        B = float(rng.choice([40e6, 300e6]))
    else:
        B = float(rng.choice([150e6, 400e6]))
    N = int(rng.choice([64, 128, 128, 256]))
    Tr = float(rng.uniform(8e-6, 40e-6))
    # PRF: mostly unaliased (> 2.2 tip) when that is within 40 kHz, else what we can
    want = 2.3 * tip_dop
    if rng.random() < 0.75 and want < 40e3:
        prf = float(rng.uniform(want, min(40e3, want * 1.6)))
    else:
        prf = float(rng.uniform(3e3, 20e3))
    prf = min(prf, 1 / (Tr * 1.05))
    dwell = float(rng.uniform(0.2, 1.5))
    # keep chirps modest and cost bounded
    max_chirps = 30000
    dwell = min(dwell, max_chirps / prf)
    n_ch = int(rng.choice([1, 1, 2, 4, 8, 16]))
    radar = make_radar(band, B, N, Tr, prf, dwell, n_ch)
    # cost guard: points per blade
    npts = (r - 0.015) / (radar["lam"] / 8)
    cost = npts * nrot * nbl * radar["M"] * N * n_ch
    while cost > 6e9 and radar["M"] > 3000:
        radar = make_radar(band, B, N, Tr, prf, radar["M"] / prf * 0.7, n_ch)
        cost = npts * nrot * nbl * radar["M"] * N * n_ch
    while cost > 6e9 and n_ch > 1:
        n_ch //= 2
        radar = make_radar(band, B, N, Tr, prf, radar["M"] / prf, n_ch)
        cost = npts * nrot * nbl * radar["M"] * N * n_ch
    dR = rbin(radar)
    Rmax = dR * N / 2
    R0 = float(rng.uniform(max(4 * dR, 3.0), min(0.7 * Rmax, 150)))
    az = float(rng.uniform(-20, 20))
    el_los = 0.0
    p0 = R0 * np.array([np.cos(np.deg2rad(az)), np.sin(np.deg2rad(az)), 0.0])
    move = rng.choice(["hover_sway", "hover_sway", "radial", "radial", "static"])
    u = fs_.unit(p0)
    if move == "radial":
        vr = float(rng.uniform(-6, 6))
        vel = vr * u
    else:
        vel = np.zeros(3)
    sway_amp = float(rng.uniform(0.02, 0.1)) if move == "hover_sway" else 0.0
    sway_hz = float(rng.uniform(0.3, 2.0))
    traj = fs_.body_traj(p0, vel, sway_amp, sway_hz, rng.normal(size=3), float(rng.uniform(0, 6.28)))
    body_amp = float(rng.uniform(0.5, 2.0))
    blade_amp = float(rng.uniform(0.4, 2.0))
    snr = float(rng.choice([20, 10, 5, 0, -5]))
    given_blades = bool(rng.random() < 0.8)
    given_el = bool(rng.random() < 0.8)
    return dict(kind="drone", band=band, radar=radar, targets=[dict(kind="drone", traj=(p0, vel, sway_amp, sway_hz),
                traj_fn=traj, body_amp=body_amp, rotors=rotors, nbl=nbl, r=r, beta=beta, profile=profile,
                blade_amp=blade_amp, gains=gains)], snr=snr, given_blades=given_blades, given_el=given_el,
                clutter=bool(rng.random() < 0.35), equal=equal, seed=sid)


def bird_scene(rng, sid, band=None):
    band = band or str(rng.choice(["X", "K", "77", "94"], p=[0.35, 0.35, 0.15, 0.15]))
    lam = C / BANDS[band]
    wb = float(rng.uniform(3, 15))
    span = float(rng.uniform(1.5, 2.2)) / wb   # semi-span ~ 1.8 m Hz / wingbeat (sparrow .13 m @14 Hz, gull .6 m @3 Hz)
    speed = float(rng.uniform(5, 15))
    if band == "X":
        B = float(rng.choice([20e6, 50e6]))
    elif band == "K":
        B = float(rng.choice([50e6, 150e6]))
    else:
        B = float(rng.choice([40e6, 150e6]))
    N = int(rng.choice([64, 128, 256]))
    Tr = float(rng.uniform(8e-6, 30e-6))
    dop = 2 * speed / lam
    prf = float(rng.uniform(max(2e3, 3 * dop), max(2e3, 3 * dop) * 1.5))
    prf = min(prf, 40e3, 1 / (Tr * 1.05))
    dwell = float(rng.uniform(0.6, 2.0))
    dwell = min(dwell, 30000 / prf)
    n_ch = int(rng.choice([1, 2, 4, 8]))
    radar = make_radar(band, B, N, Tr, prf, dwell, n_ch)
    dR = rbin(radar)
    Rmax = dR * N / 2
    travel = speed * dwell
    lo, hi = max(5 * dR, 5.0), min(0.85 * Rmax, 180)
    if hi - lo < 1.2 * travel:  # shorten the dwell so the bird stays inside the range window
        dwell = max(0.3, (hi - lo) / (1.2 * speed))
        radar = make_radar(band, B, N, Tr, prf, dwell, n_ch)
        travel = speed * dwell
    u_R = float(rng.uniform(0, 1))
    # flight: mostly towards/away, at an angle to the LOS
    az = np.deg2rad(rng.uniform(-15, 15))
    elev = np.deg2rad(rng.uniform(5, 30))  # bird above radar
    hdg_off = np.deg2rad(rng.uniform(0, 60))
    sign = rng.choice([-1, 1])
    # radial travel is at most `travel`; receding (sign>0) starts low, approaching starts high
    room = max(0.0, hi - lo - 2 * travel)
    R0 = lo + travel + u_R * room if sign > 0 else hi - travel - u_R * room
    if sign > 0 and R0 + travel > hi:   # receding bird would leave the window
        R0 = max(lo, hi - travel)
    p0 = R0 * np.array([np.cos(elev) * np.cos(az), np.cos(elev) * np.sin(az), np.sin(elev)])
    h = np.array([sign * np.cos(hdg_off), np.sin(hdg_off), 0.0])
    vel = speed * h
    traj = fs_.body_traj(p0, vel, 0.0, 1.0, [0, 0, 1], 0.0)
    snr = float(rng.choice([20, 10, 5, 0, -5]))
    return dict(kind="bird", band=band, radar=radar, targets=[dict(kind="bird", traj_fn=traj, heading=h,
                body_amp=1.0, wing_amp=float(rng.uniform(0.3, 1.0)), span=span, wb=wb,
                flap_amp=float(rng.uniform(25, 45)), fracs=(1.0,) if rng.random() < 0.6 else (0.5, 1.0),
                bob=float(rng.uniform(0, 0.01)))], snr=snr, given_blades=False, given_el=False,
                clutter=bool(rng.random() < 0.3), seed=sid)


def none_scene(rng, sid):
    band = str(rng.choice(["X", "K", "77", "94"]))
    radar = make_radar(band, 100e6, 128, 20e-6, 10e3, 0.5, 2)
    return dict(kind="none", band=band, radar=radar, targets=[], snr=0.0, given_blades=False, given_el=False,
                clutter=True, seed=sid)


# ---------------------------------------------------------------- hand-made scenes
def special(sid, rng):
    if sid == 0:  # sanity: one rotor, 2 blades, X band, high SNR, hover, no clutter
        radar = make_radar("X", 50e6, 128, 25.6e-6, 10e3, 1.0, 1)
        p0 = np.array([20.0, 0, 0])
        return dict(kind="drone", band="X", radar=radar, targets=[dict(kind="drone", traj=None,
                    traj_fn=fs_.body_traj(p0, [0, 0, 0], 0.05, 0.7, [1, 0.3, 0.2], 0.3), body_amp=1.0,
                    rotors=[dict(offset=[0, 0, 0], rate=83.7, phase=0.3)], nbl=2, r=0.12, beta=0.0,
                    profile="uniform", blade_amp=1.0, gains=[1.0, 1.0])], snr=20.0, given_blades=True,
                    given_el=True, clutter=False, seed=sid)
    if sid == 1:  # sanity: one rotor moving radially at 3 m/s (receding), K band
        radar = make_radar("K", 150e6, 128, 20e-6, 20e3, 0.8, 2)
        p0 = np.array([15.0, 2.0, 0])
        u = fs_.unit(p0)
        return dict(kind="drone", band="K", radar=radar, targets=[dict(kind="drone", traj=None,
                    traj_fn=fs_.body_traj(p0, 3.0 * u, 0, 1, [0, 0, 1], 0), body_amp=1.0,
                    rotors=[dict(offset=[0, 0, 0], rate=60.0, phase=0.3)], nbl=2, r=0.10, beta=10.0,
                    profile="uniform", blade_amp=1.0, gains=[1.0, 1.0])], snr=20.0, given_blades=True,
                    given_el=True, clutter=False, seed=sid)
    if sid == 2:  # sanity bird: X band, 6 Hz, approaching 8 m/s
        radar = make_radar("X", 20e6, 128, 20e-6, 3e3, 2.0, 1)
        p0 = np.array([80.0, 5.0, 15.0])
        h = fs_.unit([-1, 0.3, 0])
        return dict(kind="bird", band="X", radar=radar, targets=[dict(kind="bird",
                    traj_fn=fs_.body_traj(p0, 8.0 * h, 0, 1, [0, 0, 1], 0), heading=h, body_amp=1.0,
                    wing_amp=0.7, span=0.35, wb=6.0, flap_amp=40.0, fracs=(1.0,), bob=0.0)], snr=20.0,
                    given_blades=False, given_el=False, clutter=False, seed=sid)
    if 100 <= sid < 112:  # aliased equal-rate multirotors at 77/94 GHz, low PRF (pattern of s031)
        k = sid - 100
        band = ["77", "94"][k % 2]
        nbl = [3, 2, 3, 2, 3, 3][k // 2]
        nrot = [6, 6, 4, 4, 6, 2][k // 2]
        snr = [20.0, 5.0, -5.0][k % 3]
        lam = C / BANDS[band]
        r = float(rng.uniform(0.1, 0.15)); frot = float(rng.uniform(60, 90))
        prf = float(rng.uniform(5e3, 12e3))
        radar = make_radar(band, 300e6, 64, 12.8e-6, prf, min(0.5, 8000 / prf), 1)
        arm = 0.2
        rot = [dict(offset=[arm * np.cos(2 * np.pi * i / nrot), arm * np.sin(2 * np.pi * i / nrot), 0], rate=frot,
                    phase=float(i * np.pi / (2 * nbl) * (1 + (i % 2) * 0.3))) for i in range(nrot)]
        p0 = np.array([float(rng.uniform(6, 13)), 0.5, 0])
        return dict(kind="drone", band=band, radar=radar, targets=[dict(kind="drone", traj=None,
                    traj_fn=fs_.body_traj(p0, [0, 0, 0], 0.03, 0.8, [1, 0, 0.3], 0.0), body_amp=1.0, rotors=rot,
                    nbl=nbl, r=r, beta=0.0, profile=["tapered:0.3", "uniform"][k % 2], blade_amp=1.0,
                    gains=[1.0] * nbl)], snr=snr, given_blades=True, given_el=True, clutter=False, seed=sid,
                    equal=True)
    if 112 <= sid < 120:  # tip-bright / tapered blades, X and K band, high SNR, single rotor or quad
        k = sid - 112
        band = ["X", "X", "K", "K", "X", "X", "K", "X"][k]
        prof = ["tipbright", "tipbright", "tipbright", "tipbright", "tapered:0.3", "uniform", "tapered:0.3", "rough"][k]
        nrot = [1, 4, 1, 4, 4, 4, 4, 4][k]
        snr = [20.0, 20.0, 20.0, 5.0, 20.0, 20.0, 20.0, 20.0][k]
        lam = C / BANDS[band]
        r = float(rng.uniform(0.12, 0.17)); vtip = float(rng.uniform(50, 70)); frot = vtip / (2 * np.pi * r)
        tip = 2 * vtip / lam
        prf = min(40e3, 2.5 * tip)
        radar = make_radar(band, 100e6, 128, 0.9 / prf, prf, min(0.6, 20000 / prf), 1)
        rates = frot * (1 + 0.03 * np.linspace(-0.5, 0.5, nrot)) if nrot > 1 else [frot]
        rot = [dict(offset=[0.2 * np.cos(2 * np.pi * i / nrot), 0.2 * np.sin(2 * np.pi * i / nrot), 0],
                    rate=float(rates[i]), phase=float(rng.uniform(0, 6.28))) for i in range(nrot)]
        p0 = np.array([float(rng.uniform(10, 25)), 0.0, 0])
        return dict(kind="drone", band=band, radar=radar, targets=[dict(kind="drone", traj=None,
                    traj_fn=fs_.body_traj(p0, [0, 0, 0], 0.04, 0.6, [1, 0.2, 0.3], 0.0), body_amp=1.0, rotors=rot,
                    nbl=2, r=r, beta=0.0, profile=prof, blade_amp=1.0, gains=[1.0, 1.0])], snr=snr,
                    given_blades=True, given_el=True, clutter=False, seed=sid, equal=False)
    if 120 <= sid < 130:  # tip-bright blades, X band, varied
        sc = drone_scene(rng, sid, band="X")
        t = sc["targets"][0]
        t["profile"] = "tipbright"
        sc["given_blades"] = True
        sc["given_el"] = True
        sc["snr"] = float(rng.choice([20.0, 10.0]))
        return sc
    if 130 <= sid < 160:
        return bird_scene(rng, sid)
    if 160 <= sid < 180:  # 77/94 GHz drones, low PRF (aliased tips)
        sc = drone_scene(rng, sid, band=str(rng.choice(["77", "94"])))
        return sc
    if 200 <= sid < 210:  # blade imbalance (one blade 1.1-1.3x), N=2 given, X/K, unaliased
        sc = drone_scene(rng, sid, band=str(rng.choice(["X", "K"])))
        t = sc["targets"][0]
        if t["nbl"] != 2:
            t["nbl"] = 2
        t["gains"] = [1.0, float(rng.uniform(1.1, 1.3))]
        sc["given_blades"] = True
        sc["given_el"] = True
        sc["snr"] = float(rng.choice([20.0, 10.0]))
        return sc
    if 210 <= sid < 220:  # 77/94 GHz birds
        return bird_scene(rng, sid, band=str(rng.choice(["77", "94"])))
    if 220 <= sid < 380:  # general mix
        return bird_scene(rng, sid) if sid % 3 == 0 else drone_scene(rng, sid)
    if sid >= 180:
        return drone_scene(rng, sid)
    return None


def scene(sid):
    rng = np.random.default_rng(1000 + sid)
    sp = special(sid, rng)
    if sp is not None:
        return sp
    k = sid % 10
    if k in (0, 1, 2, 4, 5, 7, 8):
        return drone_scene(rng, sid)
    if k in (3, 6):
        return bird_scene(rng, sid)
    return none_scene(rng, sid) if sid % 20 == 9 else drone_scene(rng, sid)


# ---------------------------------------------------------------- build + truth
def build(sc):
    radar = sc["radar"]
    lam = radar["lam"]
    objs, truth = [], dict(kind=sc["kind"], cls=sc["kind"])
    T = radar["M"] * radar["Tp"]
    for t in sc["targets"]:
        if t["kind"] == "drone":
            d = fs_.Drone(t["traj_fn"], lam, t["body_amp"], t["rotors"], t["nbl"], t["r"], 0.015, t["beta"],
                          t["profile"], t["blade_amp"], t["gains"], rough_seed=sc["seed"])
            objs.append(d)
            rates = [ro["rate"] for ro in t["rotors"]]
            projs = [ri["proj"] for ri in d.rotor_info]
            mr = float(np.mean(rates))
            truth.update(rates=rates, rate=mr, chop=t["nbl"] * mr, nbl=t["nbl"], r=t["r"], beta=t["beta"],
                         profile=t["profile"], nrot=len(rates), pts_per_blade=d.n_pts_blade,
                         r_eff=float(t["r"] * np.mean(projs) / np.cos(np.deg2rad(t["beta"]))),
                         tip_hz=float(2 * 2 * np.pi * max(rates) * t["r"] * max(projs) / lam))
        else:
            b = fs_.Bird(t["traj_fn"], t["heading"], t["body_amp"], t["wing_amp"], t["span"], t["wb"],
                         t["flap_amp"], wing_fracs=t["fracs"], bob_m=t["bob"])
            objs.append(b)
            truth.update(wb=t["wb"], span=t["span"])
        p_s = t["traj_fn"](np.array([0.0, T]))
        R = np.linalg.norm(p_s, axis=1)
        tt = np.linspace(0, T, 2001)
        Rt = np.linalg.norm(t["traj_fn"](tt), axis=1)
        truth.update(range0=float(R[0]), body_v=float((R[1] - R[0]) / T),
                     body_moves=bool(np.ptp(Rt) > 0.01))
    if sc["clutter"]:
        rng = np.random.default_rng(sc["seed"] + 7)
        dR = rbin(radar)
        Rc = float(rng.uniform(3 * dR, 0.6 * dR * radar["N"] / 2))
        objs.append(fs_.Static([Rc, 0.5, 0.2], float(10 ** (rng.uniform(0, 30) / 20))))
        truth["clutter_R"] = Rc
    truth.update(prf=1 / radar["Tp"], dwell=T, lam=lam, M=radar["M"], N=radar["N"], nch=len(radar["rx_y"]),
                 band=sc["band"], B=radar["B"], snr=sc["snr"], given_blades=sc["given_blades"],
                 given_el=sc["given_el"], rbin=rbin(radar), Tr=radar["N"] / radar["fs"])
    return objs, truth


def capture(sc, path):
    """Scene ``sc`` built, and rendered to ``path`` unless a capture is there already (written under a temporary name,
    renamed when whole); returns its truth."""
    objs, truth = build(sc)
    if not os.path.exists(path):
        partial = os.path.splitext(path)[0] + ".part"
        fs_.render(partial, sc["radar"], objs, sc["snr"], seed=sc["seed"])
        os.replace(partial, path)
    return truth


def describe(sc, truth):
    if sc["kind"] == "drone":
        t = sc["targets"][0]
        return (f"{sc['band']} {len(t['rotors'])}x{t['nbl']}bl {'eq' if sc.get('equal') else 'uneq'} "
                f"beta{t['beta']:.0f} {t['profile']} prf{truth['prf'] / 1e3:.1f}k {truth['dwell']:.2f}s "
                f"snr{sc['snr']:.0f} ch{truth['nch']}{' +clut' if sc['clutter'] else ''}")
    if sc["kind"] == "bird":
        t = sc["targets"][0]
        return (f"{sc['band']} bird prf{truth['prf'] / 1e3:.1f}k {truth['dwell']:.2f}s snr{sc['snr']:.0f} "
                f"ch{truth['nch']}{' +clut' if sc['clutter'] else ''}")
    return f"{sc['band']} none (clutter+noise)"
