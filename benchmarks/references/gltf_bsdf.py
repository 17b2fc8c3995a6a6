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
The layers (KHR_materials_clearcoat, KHR_materials_transmission), as clpath
models them (its material_gltf.cl states the same formulas):
  clear coat c, alpha_c = clearcoat_roughness^2 (at least 1e-3), F_c = F_schlick(0.04, .):
    f = c F_c(v.h) D_c(h) G2_c(v, l) / (4 n.v n.l) + (1 - c F_c(n.v)) (1 - c F_c(n.l)) f_material
    (the extension's fresnel_coat, with the coat's Fresnel at the microfacet
    and the base attenuated both ways, which makes it reciprocal)
  transmission t (thin-walled): t of the dielectric's diffuse base becomes
    base_color (1 - F(n.v)) (1 - F(|n.l|)) D(h') G2(v, l') / (4 n.v |n.l|)
    with l' = l mirrored through the surface (z negated), h' = normalize(v + l'):
    the reflection lobe about the straight-through direction.
  The coat's normal is the shading normal (the export refuses coat normal maps).
One-sided (front only) without transmission: the export wraps it in twosided,
normalmap and mask. With transmission it is two-sided itself (a view from
below sees the mirror image of the material, as clpath's frame turned to the
viewer), since Mitsuba's twosided takes no transmitting BSDF.
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
        self.clearcoat = _texture(props, "clearcoat", 0.0)
        self.clearcoat_roughness = _texture(props, "clearcoat_roughness", 0.0)
        self.transmission = _texture(props, "transmission", 0.0)
        # Transmission makes the BSDF two-sided itself (see the top).
        self.transmits = props.get("transmits", False)
        side = mi.BSDFFlags.FrontSide | (mi.BSDFFlags.BackSide if self.transmits else mi.BSDFFlags.Empty)
        glossy = mi.BSDFFlags.GlossyReflection | side
        diffuse = mi.BSDFFlags.DiffuseReflection | side
        self.m_components = [glossy, diffuse]
        self.m_flags = glossy | diffuse
        if self.transmits:
            self.m_components.append(mi.BSDFFlags.GlossyTransmission | side)
            self.m_flags = self.m_flags | mi.BSDFFlags.GlossyTransmission

    def _params(self, si, active):
        base = self.base_color.eval(si, active)
        r = self.roughness.eval_1(si, active)
        alpha = dr.maximum(r * r, ALPHA_MIN)
        metal = dr.clip(self.metallic.eval_1(si, active), 0.0, 1.0)
        c = dr.clip(self.clearcoat.eval_1(si, active), 0.0, 1.0)
        rc = dr.clip(self.clearcoat_roughness.eval_1(si, active), 0.0, 1.0)
        t = dr.clip(self.transmission.eval_1(si, active), 0.0, 1.0)
        return base, alpha, metal, c, dr.maximum(rc * rc, ALPHA_MIN), t

    def _local(self, wi, wo):
        """The directions in the frame turned to the viewer (two-sided with transmission)."""
        if not self.transmits:
            return wi, wo
        flip = mi.Frame3f.cos_theta(wi) < 0
        s = dr.select(flip, -1.0, 1.0)
        return mi.Vector3f(wi.x, wi.y, wi.z * s), mi.Vector3f(wo.x, wo.y, wo.z * s)

    def _value(self, wi, wo, p):
        """f(wi, wo) |cos(theta_o)|, Mitsuba's naming: wi to the viewer, wo to the light."""
        base, alpha, metal, c, alpha_c, t = p
        wi, wo = self._local(wi, wo)
        ci, co = mi.Frame3f.cos_theta(wi), mi.Frame3f.cos_theta(wo)
        aco = dr.abs(co)
        under = (1.0 - c * _schlick(0.04, ci)) * (1.0 - c * _schlick(0.04, aco))
        body = (1.0 - metal) * (1.0 - _schlick(self.f0, ci)) * (1.0 - _schlick(self.f0, aco))
        # Reflection.
        h = dr.normalize(wi + wo)
        vh = dr.dot(wi, h)
        g2 = 1.0 / (1.0 + _smith_lambda(ci, alpha) + _smith_lambda(co, alpha))
        s_cos = _ggx_d(mi.Frame3f.cos_theta(h), alpha) * g2 / (4.0 * ci)  # S times n.l
        metal_part = _schlick(base, vh) * s_cos
        spec = _schlick(self.f0, vh) * s_cos
        diff = base * (body * (1.0 - t) * co / dr.pi)
        g2c = 1.0 / (1.0 + _smith_lambda(ci, alpha_c) + _smith_lambda(co, alpha_c))
        coat = c * _schlick(0.04, vh) * _ggx_d(mi.Frame3f.cos_theta(h), alpha_c) * g2c / (4.0 * ci)
        refl = under * (metal * metal_part + (1.0 - metal) * spec + diff) + coat
        # Thin-walled transmission: the reflection lobe mirrored through the surface.
        wr = mi.Vector3f(wo.x, wo.y, aco)
        hr = dr.normalize(wi + wr)
        g2r = 1.0 / (1.0 + _smith_lambda(ci, alpha) + _smith_lambda(aco, alpha))
        trans = base * (under * body * t * _ggx_d(mi.Frame3f.cos_theta(hr), alpha) * g2r / (4.0 * ci))
        val = dr.select(co > 0, refl, trans)
        ok = (ci > 0) & ((co > 0) | ((co < 0) & self.transmits))
        return dr.select(ok, val, 0.0)

    def _probabilities(self, p):
        """Lobe choice, shared with nothing in clpath: coat, specular, diffuse, transmission."""
        _, _, metal, c, _, t = p
        p_coat = dr.select(c > 0, 0.25, 0.0)
        p_spec = (1.0 - p_coat) * (0.5 + 0.5 * metal)
        rest = 1.0 - p_coat - p_spec
        p_trans = rest * t if self.transmits else 0.0 * t
        return p_coat, p_spec, rest - p_trans, p_trans

    def _pdf(self, wi, wo, p):
        _, alpha, _, _, alpha_c, _ = p
        wi, wo = self._local(wi, wo)
        ci, co = mi.Frame3f.cos_theta(wi), mi.Frame3f.cos_theta(wo)
        p_coat, p_spec, p_diff, p_trans = self._probabilities(p)
        wr = mi.Vector3f(wo.x, wo.y, dr.abs(co))
        h = dr.normalize(wi + wr)
        vh = dr.dot(wi, h)
        ch = mi.Frame3f.cos_theta(h)
        jac = ch / (4.0 * dr.abs(vh))  # Walter et al. 2007: pdf of h (D cos) to pdf of the reflected direction
        refl = p_spec * _ggx_d(ch, alpha) * jac + p_coat * _ggx_d(ch, alpha_c) * jac + p_diff * co / dr.pi
        trans = p_trans * _ggx_d(ch, alpha) * jac
        pdf = dr.select(co > 0, refl, trans)
        return dr.select((ci > 0) & (co != 0) & (vh > 0), pdf, 0.0)

    def sample(self, ctx, si, sample1, sample2, active=True):
        p = self._params(si, active)
        _, alpha, _, _, alpha_c, _ = p
        wi_world = si.wi
        wi, _ = self._local(wi_world, wi_world)
        p_coat, p_spec, p_diff, p_trans = self._probabilities(p)
        pick_coat = sample1 < p_coat
        pick_spec = ~pick_coat & (sample1 < p_coat + p_spec)
        pick_trans = sample1 >= p_coat + p_spec + p_diff
        a = dr.select(pick_coat, alpha_c, alpha)
        # Walter et al. 2007, eq. 35-36: theta_h with tan^2 = alpha^2 xi / (1 - xi).
        xi = dr.minimum(sample2.x, 0.99999994)
        tan2 = a * a * xi / (1.0 - xi)
        cos_h = 1.0 / dr.sqrt(1.0 + tan2)
        sin_h = dr.sqrt(dr.maximum(1.0 - cos_h * cos_h, 0.0))
        phi = 2.0 * dr.pi * sample2.y
        h = mi.Vector3f(sin_h * dr.cos(phi), sin_h * dr.sin(phi), cos_h)
        wo_spec = 2.0 * dr.dot(wi, h) * h - wi
        wo_trans = mi.Vector3f(wo_spec.x, wo_spec.y, -wo_spec.z)
        wo_diff = mi.warp.square_to_cosine_hemisphere(sample2)
        wo = dr.select(pick_coat | pick_spec, wo_spec, dr.select(pick_trans, wo_trans, wo_diff))
        good_side = dr.select(pick_trans, mi.Frame3f.cos_theta(wo) < 0, mi.Frame3f.cos_theta(wo) > 0)
        # Back to the world's side (the mirror of _local).
        flip = self.transmits & (mi.Frame3f.cos_theta(wi_world) < 0)
        wo = mi.Vector3f(wo.x, wo.y, dr.select(flip, -wo.z, wo.z))
        bs = mi.BSDFSample3f()
        bs.wo = wo
        bs.eta = 1.0
        bs.sampled_component = dr.select(pick_coat | pick_spec, mi.UInt32(0),
                                         dr.select(pick_trans, mi.UInt32(2), mi.UInt32(1)))
        bs.sampled_type = dr.select(pick_coat | pick_spec, mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                    dr.select(pick_trans, mi.UInt32(+mi.BSDFFlags.GlossyTransmission),
                                              mi.UInt32(+mi.BSDFFlags.DiffuseReflection)))
        bs.pdf = self._pdf(wi_world, bs.wo, p)
        ok = active & (mi.Frame3f.cos_theta(wi) > 0) & good_side & (bs.pdf > 0)
        val = self._value(wi_world, bs.wo, p)
        return bs, dr.select(ok, val / dr.select(ok, bs.pdf, 1.0), 0.0)

    def eval(self, ctx, si, wo, active=True):
        p = self._params(si, active)
        return dr.select(active, self._value(si.wi, wo, p), 0.0)

    def pdf(self, ctx, si, wo, active=True):
        p = self._params(si, active)
        return dr.select(active, self._pdf(si.wi, wo, p), 0.0)

    def eval_pdf(self, ctx, si, wo, active=True):
        p = self._params(si, active)
        return (dr.select(active, self._value(si.wi, wo, p), 0.0), dr.select(active, self._pdf(si.wi, wo, p), 0.0))

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

