"""A Mitsuba 3 BSDF plugin for the glTF 2.0 metallic-roughness material as
clpath models it, written from the published formulas (not from clpath's
kernels), so that a Mitsuba reference can check how clpath integrates the
material: next-event estimation, MIS, textures, normal maps, cut-outs.
The formula itself is checked against a double-precision reference by
clpath's material tests (tests/kernels/), not here.

    import gltf_bsdf; gltf_bsdf.register()   (after mitsuba.set_variant)
    {"type": "gltf_metallic_roughness", "base_color": <texture>, "roughness": <texture>,
     "metallic": <texture>, "ior": 1.5}

The model, in a local frame with the normal +z, v the direction to the viewer
(Mitsuba's si.wi), l the direction to the light, h = normalize(v + l):
  glTF 2.0 specification, appendix B: mix(dielectric, metal, metallic) with
    metal      = F_schlick(base_color, v.h) * S
    dielectric = F_schlick(f0, v.h) * S + (diffuse base, below)
    f0         = ((ior - 1) / (ior + 1))^2         (0.04 for ior 1.5)
  S = D(h) G2(v, l) / (4 n.v n.l): GGX D of Walter et al. 2007 (eq. 33) with
    alpha = roughness^2 (at least 1e-3, as clpath keeps it), and the
    height-correlated Smith masking-shadowing of Heitz 2014 (eq. 99):
    G2 = 1 / (1 + Lambda(v) + Lambda(l)), Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2
    (the appendix's own V term is the separable G1 G1; clpath uses this one).
  The diffuse base: base_color / pi weighted by (1 - F(n.v)) (1 - F(n.l))
    with F = F_schlick(f0, .) -- clpath's documented change from the
    appendix's 1 - F(v.h) (the weighting of Ashikhmin and Shirley 2000).
Sampling (any correct scheme serves a reference; this one shares nothing
with clpath's): with probability p the specular lobe, half vectors from
D(h) cos(theta_h) (Walter et al. 2007, eq. 35-36) reflected about h; else
cosine-weighted directions. p = 0.5 + 0.5 metallic. The pdf is the mixture's.
One-sided (front only): the export wraps it in twosided, normalmap and mask.
Also here: the threshold texture (alpha MASK) and the product texture (base
colour times vertex colours) the export uses.
"""
import drjit as dr
import mitsuba as mi

ALPHA_MIN = 1e-3


def _texture(props, name, default):
    return props.get_texture(name, default)


def _schlick(f0, c):
    m = dr.clip(1.0 - c, 0.0, 1.0)
    m2 = m * m
    return f0 + (1.0 - f0) * (m2 * m2 * m)


def _ggx_d(cos_h, alpha):
    a2 = alpha * alpha
    c2 = cos_h * cos_h
    d = c2 * (a2 - 1.0) + 1.0
    return a2 / (dr.pi * d * d)


def _smith_lambda(cos_t, alpha):
    c2 = cos_t * cos_t
    tan2 = dr.maximum(1.0 - c2, 0.0) / c2
    return 0.5 * (dr.sqrt(1.0 + alpha * alpha * tan2) - 1.0)


class GltfMetallicRoughness(mi.BSDF):
    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.base_color = _texture(props, "base_color", 0.5)
        self.roughness = _texture(props, "roughness", 1.0)
        self.metallic = _texture(props, "metallic", 0.0)
        ior = props.get("ior", 1.5)
        self.f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
        glossy = mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
        diffuse = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide
        self.m_components = [glossy, diffuse]
        self.m_flags = glossy | diffuse

    def _params(self, si, active):
        base = self.base_color.eval(si, active)
        r = self.roughness.eval_1(si, active)
        alpha = dr.maximum(r * r, ALPHA_MIN)
        metal = dr.clip(self.metallic.eval_1(si, active), 0.0, 1.0)
        return base, alpha, metal

    def _value(self, wi, wo, base, alpha, metal):
        """f(wi, wo) cos(theta_o), Mitsuba's naming: wi to the viewer, wo to the light."""
        ci, co = mi.Frame3f.cos_theta(wi), mi.Frame3f.cos_theta(wo)
        h = dr.normalize(wi + wo)
        vh = dr.dot(wi, h)
        g2 = 1.0 / (1.0 + _smith_lambda(ci, alpha) + _smith_lambda(co, alpha))
        s_cos = _ggx_d(mi.Frame3f.cos_theta(h), alpha) * g2 / (4.0 * ci)  # S times n.l
        metal_part = _schlick(base, vh) * s_cos
        coat = _schlick(self.f0, vh) * s_cos
        diff = base * ((1.0 - _schlick(self.f0, ci)) * (1.0 - _schlick(self.f0, co)) * co / dr.pi)
        val = metal * metal_part + (1.0 - metal) * (diff + coat)
        return dr.select((ci > 0) & (co > 0), val, 0.0)

    def _pdf(self, wi, wo, alpha, metal):
        ci, co = mi.Frame3f.cos_theta(wi), mi.Frame3f.cos_theta(wo)
        h = dr.normalize(wi + wo)
        vh = dr.dot(wi, h)
        p_spec = 0.5 + 0.5 * metal
        ch = mi.Frame3f.cos_theta(h)
        spec = _ggx_d(ch, alpha) * ch / (4.0 * dr.abs(vh))
        pdf = p_spec * spec + (1.0 - p_spec) * co / dr.pi
        return dr.select((ci > 0) & (co > 0) & (vh > 0), pdf, 0.0)

    def sample(self, ctx, si, sample1, sample2, active=True):
        base, alpha, metal = self._params(si, active)
        wi = si.wi
        p_spec = 0.5 + 0.5 * metal
        pick_spec = sample1 < p_spec
        # Walter et al. 2007, eq. 35-36: theta_h with tan^2 = alpha^2 xi / (1 - xi).
        xi = dr.minimum(sample2.x, 0.99999994)
        tan2 = alpha * alpha * xi / (1.0 - xi)
        cos_h = 1.0 / dr.sqrt(1.0 + tan2)
        sin_h = dr.sqrt(dr.maximum(1.0 - cos_h * cos_h, 0.0))
        phi = 2.0 * dr.pi * sample2.y
        h = mi.Vector3f(sin_h * dr.cos(phi), sin_h * dr.sin(phi), cos_h)
        wo_spec = 2.0 * dr.dot(wi, h) * h - wi
        wo_diff = mi.warp.square_to_cosine_hemisphere(sample2)
        bs = mi.BSDFSample3f()
        bs.wo = dr.select(pick_spec, wo_spec, wo_diff)
        bs.eta = 1.0
        bs.sampled_component = dr.select(pick_spec, mi.UInt32(0), mi.UInt32(1))
        bs.sampled_type = dr.select(pick_spec, mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                    mi.UInt32(+mi.BSDFFlags.DiffuseReflection))
        bs.pdf = self._pdf(wi, bs.wo, alpha, metal)
        ok = active & (mi.Frame3f.cos_theta(wi) > 0) & (mi.Frame3f.cos_theta(bs.wo) > 0) & (bs.pdf > 0)
        val = self._value(wi, bs.wo, base, alpha, metal)
        return bs, dr.select(ok, val / dr.select(ok, bs.pdf, 1.0), 0.0)

    def eval(self, ctx, si, wo, active=True):
        base, alpha, metal = self._params(si, active)
        return dr.select(active, self._value(si.wi, wo, base, alpha, metal), 0.0)

    def pdf(self, ctx, si, wo, active=True):
        _, alpha, metal = self._params(si, active)
        return dr.select(active, self._pdf(si.wi, wo, alpha, metal), 0.0)

    def eval_pdf(self, ctx, si, wo, active=True):
        base, alpha, metal = self._params(si, active)
        return (dr.select(active, self._value(si.wi, wo, base, alpha, metal), 0.0),
                dr.select(active, self._pdf(si.wi, wo, alpha, metal), 0.0))

    def to_string(self):
        return "GltfMetallicRoughness[f0=%g]" % self.f0


class Threshold(mi.Texture):
    """1 where a texture's value is at least `cutoff`, else 0: glTF's MASK
    alpha mode (the coverage is filtered first, then compared)."""

    def __init__(self, props):
        mi.Texture.__init__(self, props)
        self.nested = props.get_texture("texture")
        self.cutoff = props.get("cutoff", 0.5)

    def eval_1(self, si, active=True):
        return dr.select(self.nested.eval_1(si, active) >= self.cutoff, 1.0, 0.0)

    def eval(self, si, active=True):
        return mi.Color3f(self.eval_1(si, active))

    def mean(self):
        return 0.5

    def to_string(self):
        return "Threshold[cutoff=%g]" % self.cutoff


class Product(mi.Texture):
    """texture_0 times texture_1 (clpath's base colour times vertex colours)."""

    def __init__(self, props):
        mi.Texture.__init__(self, props)
        self.a = props.get_texture("texture_0")
        self.b = props.get_texture("texture_1")

    def eval(self, si, active=True):
        return self.a.eval(si, active) * self.b.eval(si, active)

    def eval_1(self, si, active=True):
        return self.a.eval_1(si, active) * self.b.eval_1(si, active)

    def mean(self):
        return self.a.mean() * self.b.mean()

    def to_string(self):
        return "Product"


def register():
    mi.register_bsdf("gltf_metallic_roughness", lambda props: GltfMetallicRoughness(props))
    mi.register_texture("threshold", lambda props: Threshold(props))
    mi.register_texture("product", lambda props: Product(props))

