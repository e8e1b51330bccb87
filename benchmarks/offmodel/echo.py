"""An FMCW echo simulator written apart from mdpipe's own (numpy and h5py only; nothing from mdpipe.physics or
mdpipe.simulate): blades as strips of points at most lambda / 8 apart, every IF sample of every chirp, real IF
written as int16 in the Radarlog layout. Its echoes check mdpipe's estimators on assumptions they were not
derived on (benchmarks/bench_offmodel.py).

Conventions
-----------
* Radar at the origin, x boresight, y along the RX array, z up.  TX at the origin, RX k at (0, y_k, 0).
* Chirp m starts at t_m = m*Tp; IF sample n at t_m + n/fs; sweep f(t) = f0 + S t, S = B / TRampUp,
  TRampUp = N / fs (the sampled ramp).
* Each scatterer at range R(t): two-way delay tau(t) = (|p| + |p - rx_k|)/c (far field: 2R - y_k u_y).
  Beat phase  phi_n = 2 pi (f0 tau_n + S tau_n t_n - S tau_n^2 / 2), tau_n evaluated *at every IF sample*
  through a per-chirp quadratic fit of R(t) (three exact range evaluations across the ramp) -> range
  migration, Doppler within the ramp, range-Doppler coupling all included.
  Complex sum of A * exp(j phi_n) over scatterers, real part taken (real IF, as the Radarlog stores).
* Blades: straight strips from r_root to r (truth blade length r = hub to tip), discretised at <= lambda/8
  along the span, per-point reflectivity profile (uniform / tapered / tipbright / rough), per-blade gains,
  N blades at 2 pi b / N, rotating at f_rot rev/s; rotor disc spanned by e1, e2 with e1.u = cos(beta + pitch),
  e2.u ~ -sin(roll) sin(beta) (beta = elevation of LOS over the disc plane).
* Doppler truth: body range rate dR/dt, positive receding (mdpipe's body_velocity_mps convention).
* Noise: real white Gaussian per IF sample & channel, sigma from SNR per IF sample of the moving echo
  (everything but static clutter) on channel 1; then scaled to int16 (peak 20000 counts), FuSca = 1/scale.
"""
import math

import h5py
import numpy as np

C = 299792458.0


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


# ---------------------------------------------------------------- scatterer models
# Each model: fixed per-scatterer amplitude (complex) and a function pos(t) -> (T, S, 3)

class Static:
    def __init__(self, pos, amp):
        self.p = np.asarray(pos, float)[None, None, :]
        self.amp = np.array([amp], complex)

    def pos(self, t):
        return np.broadcast_to(self.p, (len(t), 1, 3))


def body_traj(p0, vel, sway_amp, sway_hz, sway_dir, sway_phase):
    p0 = np.asarray(p0, float)
    vel = np.asarray(vel, float)
    sd = unit(sway_dir) if sway_amp else np.zeros(3)

    def f(t):
        t = np.asarray(t)[:, None]
        return p0 + vel * t + sway_amp * np.sin(2 * np.pi * sway_hz * t + sway_phase) * sd
    return f


class Drone:
    """Body point + rotors of blade strips."""

    def __init__(self, traj, lam, body_amp, rotors, n_blades, r, r_root, beta_deg, profile,
                 blade_amp, blade_gains, rough_seed=0, spacing_frac=8.0, body_extra=()):
        self.traj = traj
        p_mid = traj(np.array([0.0]))[0]
        u = unit(p_mid)
        up = np.array([0, 0, 1.0]) - u[2] * u
        up = unit(up)
        w = np.cross(u, up)
        self.rotors = []
        dr = lam / spacing_frac
        n_pts = max(4, int(math.ceil((r - r_root) / dr)))
        rho = r_root + (np.arange(n_pts) + 0.5) * (r - r_root) / n_pts
        x = (rho - r_root) / (r - r_root)
        rng = np.random.default_rng(rough_seed)
        if profile == "uniform":
            g = np.ones_like(rho)
        elif profile.startswith("tapered"):
            tip = float(profile.split(":")[1]) if ":" in profile else 0.3
            g = 1 - (1 - tip) * x
        elif profile == "tipbright":
            g = 0.4 + 1.6 * x ** 2
        elif profile == "rough":
            # correlated random amplitude (and slight phase) along the span
            k = max(3, n_pts // 20)
            raw = rng.normal(size=n_pts + k)
            sm = np.convolve(raw, np.ones(k) / k, mode="valid")[:n_pts]
            sm = (sm - sm.mean()) / (sm.std() + 1e-12)
            g = np.clip(1 + 0.35 * sm, 0.2, None)
        else:
            raise ValueError(profile)
        self.profile_g = g
        weight = g * (r - r_root) / n_pts / (r - r_root)   # coherent broadside sum = mean(g)
        pts, amps = [], []
        self.rotor_info = []
        beta = np.deg2rad(beta_deg)
        for ro in rotors:
            pitch = np.deg2rad(ro.get("pitch_deg", 0.0))
            roll = np.deg2rad(ro.get("roll_deg", 0.0))
            b = beta + pitch
            e1 = np.cos(b) * u + np.sin(b) * up
            nrm = -np.sin(b) * u + np.cos(b) * up
            e2 = np.cos(roll) * w + np.sin(roll) * nrm
            proj = math.hypot(e1 @ u, e2 @ u)
            self.rotor_info.append(dict(rate=ro["rate"], proj=proj))
            for bl in range(n_blades):
                ph = rng.uniform(-0.4, 0.4, n_pts) if profile == "rough" else np.zeros(n_pts)
                a = blade_amp * blade_gains[bl] * weight * np.exp(1j * ph)
                pts.append(dict(off=np.asarray(ro["offset"], float), e1=e1, e2=e2, rho=rho,
                                rate=ro["rate"], th0=ro["phase"] + 2 * np.pi * bl / n_blades))
                amps.append(a)
        self.blades = pts
        self.amp = np.concatenate([np.array([body_amp], complex)] +
                                  [np.array([e[1]], complex) for e in body_extra] + amps)
        self.body_extra = [np.asarray(e[0], float) for e in body_extra]
        self.n_pts_blade = n_pts

    def pos(self, t):
        hub = self.traj(t)  # (T,3)
        out = [hub[:, None, :]]
        for off in self.body_extra:
            out.append((hub + off)[:, None, :])
        for bl in self.blades:
            th = 2 * np.pi * bl["rate"] * t + bl["th0"]  # (T,)
            d = np.cos(th)[:, None] * bl["e1"] + np.sin(th)[:, None] * bl["e2"]  # (T,3)
            out.append((hub + bl["off"])[:, None, :] + bl["rho"][None, :, None] * d[:, None, :])
        return np.concatenate(out, axis=1)


class Bird:
    """Body + wing points flapping sinusoidally (each wing: points at given fractions of span)."""

    def __init__(self, traj, heading, body_amp, wing_amp, span, wb_hz, flap_amp_deg, flap_mean_deg=10.0,
                 wing_fracs=(1.0,), bob_m=0.0, phase=0.0):
        self.traj = traj
        h = unit(heading)
        z = np.array([0, 0, 1.0])
        lat = np.cross(z, h)
        if np.linalg.norm(lat) < 1e-6:
            lat = np.array([0, 1.0, 0])
        self.lat = unit(lat)
        self.z = z
        self.span, self.wb, self.A = span, wb_hz, np.deg2rad(flap_amp_deg)
        self.mean = np.deg2rad(flap_mean_deg)
        self.fracs = np.asarray(wing_fracs, float)
        self.bob = bob_m
        self.phase = phase
        wa = [wing_amp * (0.5 + 0.5 * f) for f in self.fracs]
        self.amp = np.array([body_amp] + wa + wa, complex)

    def pos(self, t):
        body = self.traj(t)
        ph = 2 * np.pi * self.wb * t + self.phase
        phi = self.mean + self.A * np.sin(ph)
        body = body + self.bob * np.cos(ph)[:, None] * self.z
        out = [body[:, None, :]]
        for side in (1, -1):
            for f in self.fracs:
                d = self.span * f * (side * np.cos(phi)[:, None] * self.lat + np.sin(phi)[:, None] * self.z)
                out.append((body + d)[:, None, :])
        return np.concatenate(out, axis=1)


# ---------------------------------------------------------------- synthesis

def synth(radar, targets, rng, chunk=None):
    """Complex-free real IF per channel: returns (static_part, moving_part) arrays (n_ch, M, N) float64."""
    f0, B, N, fs, Tp, M = radar["f0"], radar["B"], radar["N"], radar["fs"], radar["Tp"], radar["M"]
    ry = np.asarray(radar["rx_y"], float)
    Tr = N / fs
    S = B / Tr
    fc = f0 + B / 2
    tn = np.arange(N) / fs
    tc = Tr / 2
    h = Tr / 2
    out_static = np.zeros((len(ry), M, N))
    out_moving = np.zeros((len(ry), M, N))
    for tgt in targets:
        amp = tgt.amp
        Sn = len(amp)
        mc = chunk or max(8, min(512, int(4e6 // (Sn * N))))
        dest = out_static if isinstance(tgt, Static) else out_moving
        for m0 in range(0, M, mc):
            m = np.arange(m0, min(M, m0 + mc))
            tm = m * Tp
            t3 = np.concatenate([tm + tc - h, tm + tc, tm + tc + h])
            P = tgt.pos(t3)  # (3*mc, S, 3)
            Rr = np.linalg.norm(P, axis=-1)
            uy = P[..., 1] / Rr
            k = len(m)
            Rm, R0, Rp = Rr[:k], Rr[k:2 * k], Rr[2 * k:]
            v = (Rp - Rm) / (2 * h)
            a = (Rp - 2 * R0 + Rm) / h ** 2
            uy0 = uy[k:2 * k]
            # per-sample range, exact quadratic in dt = tn - tc
            dt = tn - tc
            amp_r = amp[None, :]  # constant amplitude over the dwell (no 1/R^2 change)
            # two-way delay (channel 1 reference: y=0 RX); channel offsets applied as phase via u_y
            tau0 = 2 * R0 / C
            tau1 = 2 * v / C
            tau2 = a / C
            fref = f0 + S * tc
            c0 = fref * tau0 - S * tau0 ** 2 / 2
            c1 = fref * tau1 + S * tau0 - S * tau0 * tau1
            c2 = fref * tau2 + S * tau1
            for ch, y in enumerate(ry):
                # far-field RX offset: path shorter by y*u_y -> delay -y u_y / c (phase at every sample)
                dtau = -y * uy0 / C
                c0k = c0 + fref * dtau - S * tau0 * dtau
                c1k = c1 + S * dtau
                ph0 = 2 * np.pi * np.mod(c0k + c1k * dt[0] + c2 * dt[0] ** 2, 1.0)
                d1 = 2 * np.pi * (c1k / fs + c2 * (2 * dt[0] / fs + 1 / fs ** 2))
                d2 = 2 * np.pi * 2 * c2 / fs ** 2
                z = (amp_r * np.exp(1j * ph0)).astype(np.complex128)
                wv = np.exp(1j * d1)
                q = np.exp(1j * d2)
                acc = np.empty((k, N))
                for n in range(N):
                    acc[:, n] = z.real.sum(axis=1)
                    z *= wv
                    wv *= q
                dest[ch, m] += acc
    return out_static, out_moving


def write_h5(path, radar, data, fusca):
    with h5py.File(path, "w") as f:
        f.attrs["fStrt"] = float(radar["f0"])
        f.attrs["fStop"] = float(radar["f0"] + radar["B"])
        f.attrs["TRampUp"] = float(radar["N"] / radar["fs"])
        f.attrs["TRampDo"] = float(max(radar["Tp"] - radar["N"] / radar["fs"], 0) * 0.5)
        f.attrs["Tp"] = float(radar["Tp"])
        f.attrs["fs"] = float(radar["fs"])
        f.attrs["N"] = np.int64(radar["N"])
        f.attrs["NrChn"] = np.int64(data.shape[0])
        f.attrs["FuSca"] = float(fusca)
        f.attrs["Creator"] = "mdpipe benchmarks/offmodel echo"
        for ch in range(data.shape[0]):
            f.create_dataset(f"Chn{ch + 1}", data=data[ch], chunks=(min(1024, data.shape[1]), data.shape[2]))
        f.create_dataset("RxPosn", data=np.asarray(radar["rx_y"], float))


def render(path, radar, targets, snr_db, seed):
    rng = np.random.default_rng(seed)
    st, mv = synth(radar, targets, rng)
    mti = mv[0] - mv[0].mean(axis=0, keepdims=True)   # SNR of what a static removal keeps
    p_sig = np.mean(mti ** 2)
    sigma = math.sqrt(p_sig / 10 ** (snr_db / 10)) if p_sig > 0 else 1e-3
    x = st + mv + sigma * rng.standard_normal(mv.shape)
    scale = 20000.0 / np.max(np.abs(x))
    data = np.round(x * scale).astype(np.int16)
    write_h5(path, radar, data, 1.0 / scale)
    return dict(p_sig=p_sig, sigma=sigma)
