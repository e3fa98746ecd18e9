// The environment's light at a fragment of the surface program (pbr_fragment.glsl), after
// Filament's surface_light_indirect.fs: the split sum's image-based lighting under the sheen
// and the coat (ibl.glsl, Karis 2013), with the occluders' shadows (occluders.glsl), and the
// specular BTDF's light from the opaque frame behind the surface (transmission.glsl).
// Included by pbr_fragment.glsl after its Shading and transmission_weights, which it reads.

// Image-based lighting.
uniform vec3 uSH[9];
uniform int uSpecularLevels;
uniform vec2 uIblRotation;  // world_to_env (equirect.glsl) for the baked cubes
uniform float uIblScale;
layout(binding = BINDING_SPECULAR_CUBE) uniform samplerCube uSpecularCube;
layout(binding = BINDING_IRRADIANCE_CUBE) uniform samplerCube uIrradianceCube;

// The environment's irradiance at world normal n (IRRADIANCE_SH: the nine terms, else the
// irradiance cube): what the diffuse lobe is lit by, and (occluders.glsl) the light a proxy
// hides and its sides send, so that those are what that lobe would have from the
// environment. With the proxies' terms written out the SH sums cost llvmpipe less than the
// cube's fetches; in a loop over the proxies they cost more (docs/benchmarks_archive.md,
// "The proxies' terms written out").
vec3 environment_irradiance(vec3 n) {
#if IRRADIANCE_SH
  return max(eval_sh_irradiance(uSH, world_to_env(n, uIblRotation)), vec3(0.0));
#else
  return textureLod(uIrradianceCube, world_to_env(n, uIblRotation), 0.0).rgb;
#endif
}

// The sheen's image-based lighting: sheenColor times the sheen's directional albedo E(n.v)
// (the split sum's DG term for the README's Charlie visibility, ibl/sheen_lut.h) times the
// environment's order-2 SH averaged over the Charlie lobe itself (sheen.glsl's
// sheen_sh_radiance, from the lobe's tabulated first and second moments: where it gathers
// light, on the viewer's side of n, and how widely; MODEL.md "Sheen maps"). The Khronos
// Sample Viewer's getIBLRadianceCharlie looks its Charlie-prefiltered cube up along R
// instead, the other side of n, so its rims show the environment beside the object where
// the lobe back-scatters what lies behind the viewer (docs/SPLIT_SUM_ERRORS.md).
vec3 sheen_ibl(vec3 n, vec3 v, vec3 sheen_color, float sheen_roughness) {
  vec3 light = sheen_sh_radiance(uSheenLut, uSH, world_to_env(n, uIblRotation),
                                 world_to_env(v, uIblRotation), sheen_roughness);
  return max(light, vec3(0.0)) * sheen_color * sheen_E(uSheenLut, dot(n, v), sheen_roughness);
}

// The environment's light reflected (and with diffuse transmission, transmitted) towards
// the viewer: the split sum's lobes under the sheen and the coat, times the occlusion
// (`through`, `dt_weight`: transmission_weights).
vec3 image_based_light(MaterialInputs m, Shading s, float through, vec3 dt_weight) {
  vec3 n = m.n, v = s.v, wo = s.wo;
  float ao = material_occlusion();
#if IBL_OCCLUDERS
  vec3 bounce;
  vec3 visibility = occluder_visibility(vPosition, n, vSlot, bounce);
#else
  const vec3 visibility = vec3(1.0);
#endif
  vec3 prefiltered;
#if MATERIAL_ANISOTROPY
  // The anisotropic lobe's own radiance (anisotropy_ibl.glsl: taps along the stretched
  // lobe), divided by the isotropic table's albedo E = A + B that ibl_shading multiplies
  // back (through F0 A + B), so the single scattering is the lobe's and the
  // multiple-scattering and diffuse terms keep the table's, as in the path tracer.
  if (m.layer.anisotropy > 0.0) {
#if GEOMETRY == 0 && MULTISCATTER
    vec2 ab_aniso = s.brdf.ab_o;  // the IBL's table is the bound Brdf's (see below)
#else
    vec2 ab_aniso = energy_AB(uEnergyIBL, max(wo.z, 1e-4), s.brdf.table_roughness);
#endif
    prefiltered = anisotropic_ibl_radiance(uSpecularCube, uSpecularLevels, uAnisotropicAlbedo,
                                           m.frame, uIblRotation, wo, s.brdf.alpha_x,
                                           s.brdf.alpha_y) /
                  max(ab_aniso.x + ab_aniso.y, 1e-4);
  } else
#endif
    prefiltered = textureLod(uSpecularCube, world_to_env(reflect(-v, n), uIblRotation),
                             roughness_lod(s.brdf.roughness, uSpecularLevels)).rgb;
#if OCCLUDER_BOUNCE
  // The opaque proxies' light in the place of the environment's they hide: visibility L +
  // bounce in all, written as L + bounce / visibility under the visibility applied below
  // (the lobes from the prefiltered and the irradiance terms are linear in them). The
  // reflected part takes the change's cosine-weighted mean, as a rough lobe would see it.
  vec3 unshadowed_bounce = bounce / max(visibility, vec3(1e-4));
  prefiltered = max(prefiltered + unshadowed_bounce, vec3(0.0));
#endif
#if MATERIAL_TRANSMISSION && MATERIAL_VOLUME && GLASS_REFLECTIONS
  {
    // Where the mirror direction meets the opaque frame on the screen, the surface reflects
    // the frame (a wall, the floor) rather than the environment behind it; the frame's
    // colour is final radiance, already shadowed and scaled, so the scale and visibility
    // applied below are divided out of it.
    vec3 seen;
    if (uIblScale > 0.0 &&
        reflected_frame(vPosition, reflect(-v, n), uViewProjection, uInverseViewProjection,
                        uTransmissionDepth, uTransmissionFrame,
                        log2(uTransmissionFrameSize.x) * clamp(m.roughness, 0.0, 1.0), seen))
      prefiltered = seen / (uIblScale * max(visibility, vec3(1e-4)));
  }
#endif
  vec3 irradiance = environment_irradiance(n);
#if OCCLUDER_BOUNCE
  irradiance = max(irradiance + kPi * unshadowed_bounce, vec3(0.0));
#endif
#if GEOMETRY == 0 && MULTISCATTER
  // reference: the IBL's energy table is the punctual lights' (both height-correlated
  // Smith), so the bound Brdf is the IBL's too and brdf_at has looked up (A, B) at n.v
  // already (two of the compensation's fetches and a make_brdf fewer per fragment).
  Brdf ibl = s.brdf;
  vec3 indirect = wo.z >= 1e-4 ? ibl_shading_ab(ibl, uEnergyIBL, wo.z, ibl.ab_o, prefiltered, irradiance)
                               : ibl_shading(ibl, uEnergyIBL, wo.z, prefiltered, irradiance);
#else
  Brdf ibl = make_brdf(m.layer, GEOMETRY, MULTISCATTER != 0, FRESNEL, uEnergyIBL);
  vec3 indirect = ibl_shading(ibl, uEnergyIBL, dot(n, v), prefiltered, irradiance);
#endif
  indirect = ibl_lobes(indirect, ibl, uEnergyIBL, dot(n, v), irradiance);
#if MATERIAL_TRANSMISSION || MATERIAL_DIFFUSE_TRANSMISSION
  {
    // The diffuse lobe's environment light: E(n) for the part that stays, dt E(-n) for the
    // diffuse BTDF; the specular BTDF's light is the frame's (transmitted_light).
    vec3 irradiance_back = environment_irradiance(-n);
    Brdf ibl_dt = ibl;
    ibl_dt.base_color = m.dt_color;
    indirect += lobe(DEBUG_DIFFUSE, ibl_diffuse(ibl_dt, uEnergyIBL, dot(n, v), dt_weight * irradiance_back) -
                                        ibl_diffuse(ibl, uEnergyIBL, dot(n, v), through * irradiance));
  }
#endif
#if MATERIAL_SHEEN
  {
    // The base under the sheen, scaled as bsdf.h's min(1 - c E(n.v), 1 - c E(n.l)) scales
    // it under a uniform environment: by 1 - c E_max_avg(n.v), the light's side averaged
    // over a cosine lobe (core/sheen.h; the README's one-sided 1 - c E(n.v) left the base
    // up to 20% brighter than the path tracer's at normal incidence).
    float sr = clamp(m.sheen_roughness, kMinSheenRoughness, 1.0);
    vec3 sc = clamp(m.sheen_color, 0.0, 1.0);
    indirect = lobe(DEBUG_SHEEN, sheen_ibl(n, v, sc, sr)) +
               (1.0 - max3(sc) * sheen_E_max_avg(uSheenLut, dot(n, v), sr)) * indirect;
  }
#endif
#if MATERIAL_CLEARCOAT
  {
    float cw = saturate(m.coat_weight);
    float ncv = dot(m.n_coat, v);
    float cr = clamp(m.coat_roughness, kMinRoughness, 1.0);
    vec3 coat_prefiltered = textureLod(uSpecularCube, world_to_env(reflect(-v, m.n_coat), uIblRotation),
                                       roughness_lod(cr, uSpecularLevels)).rgb;
    indirect = lobe(DEBUG_CLEARCOAT, coat_ibl(cw, cr, uEnergyCoat, ncv, coat_prefiltered)) +
               (1.0 - cw * coat_fresnel(abs(ncv))) * indirect;
  }
#endif
  return ao * visibility * uIblScale * indirect;
}

#if MATERIAL_TRANSMISSION
// KHR_materials_transmission: the specular BTDF's light is what the opaque frame shows
// through the surface (transmission.glsl), through the diffuse lobe's slot under the
// dielectric's specular and base colour, then under the sheen and the coat.
vec3 transmitted_light(MaterialInputs m, Shading s, float transmission, float thickness) {
  vec3 n = m.n, v = s.v;
  TransmissionInputs t;
  t.position = vPosition;
  t.n = n;
  t.v = v;
  // The material's perceptual roughness, as the Sample Viewer's getIBLVolumeRefraction reads
  // it: a smooth surface reads the frame's level 0 alone (kMinRoughness bounds the GGX
  // lobes, not this blur), so a frame whose transmissive surfaces are all smooth needs no
  // mip chain (renderer.cpp).
  t.roughness = clamp(m.roughness, 0.0, 1.0);
#if MATERIAL_DISPERSION
  t.iors = dispersion_iors(uIor, uDispersion);
#else
  t.iors = vec3(uIor);
#endif
  t.thickness = thickness;
  t.model_scale = uModelScale;
  t.attenuation_color = uAttenuationColor;
  t.attenuation_distance = uAttenuationDistance;
#if MATERIAL_VOLUME
  vec3 seen = thick_refracted_radiance(
      t, uBackFaces != 0, uTransmissionFrame, uTransmissionDepth, uTransmissionFrameSize,
      uBackPosition, uBackNormal, uBackFaceRect, gl_FragCoord.xy / uTransmissionFrameSize,
      uViewProjection, uInverseViewProjection, uSpecularCube, uIblRotation, uSpecularLevels,
      IBL != 0 ? uIblScale : 0.0, MATERIAL_DISPERSION != 0);
#else
  vec3 seen = refracted_radiance(t, uTransmissionFrame, uTransmissionFrameSize, uViewProjection,
                                 uCameraPosition, uSpecularCube, uIblRotation, uSpecularLevels,
                                 IBL != 0 ? uIblScale : 0.0, MATERIAL_DISPERSION != 0);
#endif
  Brdf tb = make_brdf(m.layer, GEOMETRY, MULTISCATTER != 0, FRESNEL, uEnergyIBL);
  vec3 transmitted = ibl_diffuse(tb, uEnergyIBL, dot(n, v), kPi * transmission * seen);
#if MATERIAL_SHEEN
  transmitted *= 1.0 - max3(clamp(m.sheen_color, 0.0, 1.0)) *
                           sheen_E(uSheenLut, dot(n, v), clamp(m.sheen_roughness, kMinSheenRoughness, 1.0));
#endif
#if MATERIAL_CLEARCOAT
  transmitted *= 1.0 - saturate(m.coat_weight) * coat_fresnel(abs(dot(m.n_coat, v)));
#endif
  return lobe(DEBUG_TRANSMISSION, transmitted);
}
#endif
