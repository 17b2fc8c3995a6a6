"""Where clpath's material models and the Mitsuba 3 plugins the export maps
them to differ, in numbers (benchmarks/references/README.md quotes them):
  1. principled (metallic 1) against clpath's conductor, BSDF values at a few
     directions (Mitsuba's eval against clpath's formula, both G forms);
  2. directional albedo with separable Smith masking (Mitsuba) against the
     height-correlated form (clpath), conductor and rough dielectric, by
     Monte Carlo over uniformly sampled directions;
  3. Schlick against the exact conductor Fresnel of roughconductor, with F0
     matched at normal incidence;
  4. the glTF material (metallic 0): the reference plugin (gltf_bsdf.py)
     against a numpy transcription of the formulas, and how far Mitsuba's
     own principled (metallic 0) and roughplastic are from it: directional
     albedo by Monte Carlo over uniformly sampled directions (each model's
     own eval), and the albedo of the glTF appendix's 1 - F(v.h) weighting.

    python model_differences.py     (the Python of benchmarks/references/venv.sh)
"""
import math

import numpy as np
import drjit as dr
import mitsuba as mi

mi.set_variant("scalar_rgb")
rng = np.random.default_rng(1)
N = 4_000_000


def lam(c, a):
    c2 = c * c
    t2 = np.maximum(0, 1 - c2) / c2
    return 0.5 * (np.sqrt(1 + a * a * t2) - 1)


def ggx_d(hz, a):
    a2 = a * a
    d = hz * hz * (a2 - 1) + 1
    return a2 / (np.pi * d * d)


def fresnel_dielectric(ci, eta):
    ci = np.clip(ci, 0, 1)
    s2 = (1 - ci * ci) / (eta * eta)
    ct = np.sqrt(np.maximum(0, 1 - s2))
    rp = (eta * ci - ct) / (eta * ci + ct)
    rs = (ci - eta * ct) / (ci + eta * ct)
    return np.where(s2 >= 1, 1, 0.5 * (rp * rp + rs * rs))


def fresnel_conductor(ci, n, k):
    c2 = ci * ci
    s2 = 1 - c2
    t0 = n * n - k * k - s2
    a2b2 = np.sqrt(t0 * t0 + 4 * n * n * k * k)
    a = np.sqrt(0.5 * (a2b2 + t0))
    rs = (a2b2 + c2 - 2 * a * ci) / (a2b2 + c2 + 2 * a * ci)
    rp = rs * (c2 * a2b2 + s2 * s2 - 2 * a * ci * s2) / (c2 * a2b2 + s2 * s2 + 2 * a * ci * s2)
    return 0.5 * (rs + rp)


def sphere(n):
    z = rng.uniform(-1, 1, n)
    p = rng.uniform(0, 2 * np.pi, n)
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(p), r * np.sin(p), z], 1)


def view(deg):
    return np.array([math.sin(math.radians(deg)), 0, math.cos(math.radians(deg))])


print("1. principled (metallic 1) eval against clpath's conductor formula, F0 (0.95, 0.64, 0.54)")
f0 = np.array([0.95, 0.64, 0.54])
for r in (0.09, 0.5):
    b = mi.load_dict({"type": "principled", "base_color": {"type": "rgb", "value": f0.tolist()}, "metallic": 1.0,
                      "roughness": r, "specular": 0.5, "spec_tint": 0.0, "anisotropic": 0.0, "sheen": 0.0,
                      "clearcoat": 0.0, "spec_trans": 0.0})
    for ti, to in ((0.3, 0.3), (0.8, 0.2), (1.2, 0.5)):
        wi = np.array([math.sin(ti), 0, math.cos(ti)])
        wo = np.array([-math.sin(to), 0.1, math.cos(to)])
        wo /= np.linalg.norm(wo)
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.wi = mi.Vector3f(*wo)
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        si.n = mi.Vector3f(0, 0, 1)
        m = np.array(b.eval(mi.BSDFContext(), si, mi.Vector3f(*wi)))
        h = (wi + wo) / np.linalg.norm(wi + wo)
        a = r * r
        F = f0 + (1 - f0) * (1 - wo @ h) ** 5
        base = F * ggx_d(h[2], a) / (4 * wo[2])
        lo, li = lam(wo[2], a), lam(wi[2], a)
        print("  roughness %.2f theta_i %.1f theta_o %.1f: Mitsuba %s clpath %s (separable G: %s)"
              % (r, ti, to, np.round(m, 6), np.round(base / (1 + lo + li), 6), np.round(base / (1 + lo) / (1 + li), 6)))

print("2. directional albedo, separable / height-correlated Smith masking")
for r in (0.09, 0.3, 0.5):
    a = r * r
    for th in (0, 45, 75):
        wo = view(th)
        wi = sphere(N)
        wi[:, 2] = np.abs(wi[:, 2])
        h = wi + wo
        h /= np.linalg.norm(h, axis=1)[:, None]
        lo, li = lam(wo[2], a), lam(wi[:, 2], a)
        base = ggx_d(h[:, 2], a) / (4 * wo[2]) * 2 * np.pi
        print("  conductor (F = 1) roughness %.2f, view %2d deg: ratio %.4f"
              % (r, th, (base / (1 + lo) / (1 + li)).mean() / (base / (1 + lo + li)).mean()))
eta, a = 1.45, 0.3 * 0.3
for th in (0, 45, 75):
    wo = view(th)
    wi = sphere(N)
    refl = wi[:, 2] > 0
    h = np.where(refl[:, None], wi + wo, wo + eta * wi)
    h /= np.linalg.norm(h, axis=1)[:, None]
    h *= np.sign(h[:, 2])[:, None]
    woh, wih = h @ wo, np.sum(wi * h, 1)
    ok = (woh > 0) & np.where(refl, wih > 0, wih < 0)
    F = fresnel_dielectric(woh, eta)
    d = ggx_d(h[:, 2], a)
    den = woh + eta * wih
    f = np.where(refl, F * d / (4 * wo[2]), (1 - F) * d * np.abs(wih) * woh / (wo[2] * den * den)) * ok * 4 * np.pi
    lo, li = lam(wo[2], a), lam(np.abs(wi[:, 2]), a)
    print("  rough dielectric eta 1.45 roughness 0.30, view %2d deg: R+T ratio %.4f"
          % (th, (f / (1 + lo) / (1 + li)).mean() / (f / (1 + lo + li)).mean()))

print("3. Schlick against the exact conductor Fresnel with the same F0 (eta 0.2, k chosen)")
ci = np.linspace(1e-4, 1, 100001)
for F0 in (0.54, 0.9, 0.95):
    n = 0.2
    k = math.sqrt((F0 * (n + 1) ** 2 - (n - 1) ** 2) / (1 - F0))
    fs = F0 + (1 - F0) * (1 - ci) ** 5
    fc = fresnel_conductor(ci, n, k)
    hemi = lambda f: 2 * np.trapezoid(f * ci, ci)  # noqa: E731
    print("  F0 %.2f (k %.3f): max |difference| %.4f at cos %.3f; hemispherical exact / Schlick %.4f"
          % (F0, k, np.max(np.abs(fs - fc)), ci[np.argmax(np.abs(fs - fc))], hemi(fc) / hemi(fs)))

print("4. glTF material, metallic 0, base colour 0.8, ior 1.5 (F0 0.04): directional albedo")
mi.set_variant("llvm_ad_rgb")
import sys  # noqa: E402
import os  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_bsdf  # noqa: E402
gltf_bsdf.register()
M = 1_000_000
f0g, base = 0.04, 0.8


def schlick(f0, c):
    return f0 + (1 - f0) * np.clip(1 - c, 0, 1) ** 5


def mitsuba_albedo(b, wo, dirs):
    """Directional albedo and the values, from the plugin's eval, with wo towards the viewer."""
    si = dr.zeros(mi.SurfaceInteraction3f, len(dirs))
    si.wi = mi.Vector3f(*[mi.Float(np.full(len(dirs), x, np.float32)) for x in wo])
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    si.n = mi.Vector3f(0, 0, 1)
    v = np.array(b.eval(mi.BSDFContext(), si, mi.Vector3f(*[mi.Float(dirs[:, k].astype(np.float32)) for k in range(3)])))
    return v[0].mean() * 2 * np.pi, v[0]


for r in (0.3, 0.5):
    a = max(r * r, 1e-3)
    plugin = mi.load_dict({"type": "gltf_metallic_roughness", "base_color": {"type": "rgb", "value": [base] * 3},
                           "roughness": r, "metallic": 0.0, "ior": 1.5})
    principled = mi.load_dict({"type": "principled", "base_color": {"type": "rgb", "value": [base] * 3},
                               "metallic": 0.0, "roughness": r, "specular": 0.5, "spec_tint": 0.0, "anisotropic": 0.0,
                               "sheen": 0.0, "clearcoat": 0.0, "spec_trans": 0.0})
    plastic = mi.load_dict({"type": "roughplastic", "distribution": "ggx", "alpha": a, "int_ior": 1.5, "ext_ior": 1.0,
                            "diffuse_reflectance": {"type": "rgb", "value": [base] * 3}, "nonlinear": False})
    for th in (0, 45, 75):
        wo = view(th)
        wi = sphere(M)
        wi[:, 2] = np.abs(wi[:, 2])
        h = wi + wo
        h /= np.linalg.norm(h, axis=1)[:, None]
        vh = h @ wo
        spec = ggx_d(h[:, 2], a) / (4 * wo[2]) / (1 + lam(wo[2], a) + lam(wi[:, 2], a))  # f cos
        coat = schlick(f0g, vh) * spec
        diff = base / np.pi * wi[:, 2]
        ours = coat + (1 - schlick(f0g, wo[2])) * (1 - schlick(f0g, wi[:, 2])) * diff
        appendix = coat + (1 - schlick(f0g, vh)) * diff
        a_plugin, v_plugin = mitsuba_albedo(plugin, wo, wi)
        a_prin, _ = mitsuba_albedo(principled, wo, wi)
        a_plas, _ = mitsuba_albedo(plastic, wo, wi)
        rel = np.max(np.abs(v_plugin - ours) / np.maximum(np.abs(ours), 1e-6))
        si = dr.zeros(mi.SurfaceInteraction3f, M)
        si.wi = mi.Vector3f(*[mi.Float(np.full(M, x, np.float32)) for x in wo])
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        u = rng.random((3, M)).astype(np.float32)
        _, w = plugin.sample(mi.BSDFContext(), si, mi.Float(u[0]), mi.Point2f(mi.Float(u[1]), mi.Float(u[2])))
        w = np.array(w)[0]
        print("  roughness %.1f, view %2d deg: plugin's sampled weight %.4f +- %.4f against its albedo below"
              % (r, th, w.mean(), w.std() / math.sqrt(M)))
        se = v_plugin.std() * 2 * np.pi / math.sqrt(M)
        print("  roughness %.1f, view %2d deg: plugin %.4f +- %.4f (formulas %.4f, max rel. value diff %.1e); "
              "principled %.4f (x %.3f); roughplastic %.4f (x %.3f); appendix 1 - F(v.h) weighting %.4f (x %.3f)"
              % (r, th, a_plugin, se, ours.mean() * 2 * np.pi, rel, a_prin, a_prin / a_plugin, a_plas, a_plas / a_plugin,
                 appendix.mean() * 2 * np.pi, appendix.mean() * 2 * np.pi / a_plugin))
