#pragma once
// The model's BRDF (core/brdf.h's Brdf) at one path vertex, where wo is fixed and the
// path tracer asks for eval and pdf of the light sample's direction and for a BSDF sample
// (itself an eval and a pdf of the sampled direction). Brdf's methods each start from
// scratch; here what depends on wo alone (the lobe-selection probability with its albedo
// table lookup, Smith's Lambda(wo), the Lambertian term, the compensation's albedos of wo)
// is computed once per vertex, and eval and pdf of one direction share the half vector, D
// and F. Every operation is Brdf's, in Brdf's order, so every value is bit-identical to
// Brdf's (tests/pt/vertex_brdf_test.cpp compares all models and options): a change to
// Brdf (core/brdf.cpp) must be mirrored here, and that test says so when it is not.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "pbrkit/core/brdf.h"
#include "pbrkit/core/color.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/math.h"
#include "pbrkit/core/microfacet.h"
#include "pbrkit/core/sampling.h"

namespace pbrkit {

class VertexBrdf {
 public:
  /// `wo` in the local shading frame.
  VertexBrdf(const Brdf& brdf, glm::vec3 wo)
      : wo_(wo),
        base_color_(brdf.base_color()),
        metallic_(brdf.metallic()),
        roughness_(brdf.roughness()),
        alpha_(brdf.alpha()),
        F0_(brdf.F0()),
        geometry_(direct_geometry(brdf.options().model)),
        multiscatter_(brdf.options().multiscatter),
        table_(&EnergyTable::get(geometry_)) {
    // Brdf's constructor: the compensation state.
    if (multiscatter_) {
      const glm::vec2 ab_avg = table_->AB_avg(roughness_);
      E_avg_ = ab_avg.x + ab_avg.y;
      Fms_ = multiscatter_fresnel(F0_, E_avg_);
      Es_avg_ = F0_ * ab_avg.x + ab_avg.y + Fms_ * (1.0f - E_avg_);
    }
    // Brdf::specular_probability(wo).
    {
      const float mu = std::max(wo.z, 0.0f);
      const glm::vec2 ab = table_->AB(mu, roughness_);
      const glm::vec3 Ess = F0_ * ab.x + ab.y;
      const float spec = luminance(Ess);
      float rest = (1.0f - metallic_) * luminance(base_color_) * (1.0f - spec);
      if (multiscatter_) rest += luminance(Fms_) * (1.0f - (ab.x + ab.y));
      const float total = spec + rest;
      p_spec_ = total > 0.0f ? spec / total : 1.0f;
    }
    lambert_ = (1.0f - metallic_) * base_color_ * kInvPi;
    if (wo.z > 0.0f) {
      if (geometry_ == GeometryModel::kReference) {
        lambda_o_ = SmithLambdaGGX(wo, alpha_);
        G1_o_ = 1.0f / (1.0f + lambda_o_);  // SmithG1GGX(wo, alpha)
      } else {
        G1_o_ = SmithG1GGX(wo, alpha_);
        schlick_o_ = GeometrySchlickGGX(std::max(wo.z, 0.0f), k_schlick());
      }
      if (multiscatter_) {
        Es_o_ = specular_albedo(wo.z);
        E_o_ = table_->E(wo.z, roughness_);
      }
    }
  }

  /// Brdf::eval(wo, wi), and Brdf::pdf(wo, wi) in `pdf` unless it is null.
  glm::vec3 eval(glm::vec3 wi, float* pdf = nullptr) const {
    const glm::vec3 wo = wo_;
    if (wo.z <= 0.0f || wi.z <= 0.0f) {
      if (pdf) *pdf = 0.0f;
      return glm::vec3(0.0f);
    }
    const glm::vec3 h = glm::normalize(wo + wi);
    const float WOdotH = glm::dot(wo, h);
    const float D = DistributionGGX(h, alpha_);
    // Brdf::eval_specular: D G F / (4 (n.l)(n.v)).
    const glm::vec3 F = fresnelSchlick(std::max(WOdotH, 0.0f), F0_);
    float G;
    if (geometry_ == GeometryModel::kReference)
      G = 1.0f / (1.0f + lambda_o_ + SmithLambdaGGX(wi, alpha_));  // SmithG2HeightCorrelated
    else
      G = schlick_o_ * GeometrySchlickGGX(std::max(wi.z, 0.0f), k_schlick());
    const glm::vec3 specular = D * G * F / (4.0f * wo.z * wi.z);
    // Brdf::eval_diffuse_and_ms.
    glm::vec3 diffuse;
    if (!multiscatter_) {
      diffuse = (1.0f - F) * lambert_;
    } else {
      const glm::vec3 Es_i = specular_albedo(wi.z);
      diffuse =
          lambert_ * (1.0f - Es_o_) * (1.0f - Es_i) / glm::max(1.0f - Es_avg_, glm::vec3(1e-6f));
      const float E_i = table_->E(wi.z, roughness_);
      diffuse =
          diffuse + Fms_ * ((1.0f - E_o_) * (1.0f - E_i) / (kPi * std::max(1.0f - E_avg_, 1e-6f)));
    }
    if (pdf) {
      // Brdf::pdf: ggx_vndf_pdf (G1(wo) (wo.h) D(h) / wo.z), reflected, mixed with the
      // cosine lobe.
      const float pdf_h = WOdotH <= 0.0f ? 0.0f : G1_o_ * WOdotH * D / wo.z;
      const float pdf_spec = reflected_pdf(pdf_h, WOdotH);
      *pdf = p_spec_ * pdf_spec + (1.0f - p_spec_) * cosine_hemisphere_pdf(wi.z);
    }
    return specular + diffuse;
  }

  /// Brdf::sample(wo, u_lobe, u).
  BrdfSample sample(float u_lobe, glm::vec2 u) const {
    BrdfSample s;
    if (wo_.z <= 0.0f) return s;
    if (u_lobe < p_spec_) {
      s.wi = reflect_about(wo_, vndf_half_vector(u));
    } else {
      s.wi = sample_cosine_hemisphere(u).direction;
    }
    if (s.wi.z <= 0.0f) return s;
    const glm::vec3 f = eval(s.wi, &s.pdf);
    if (!(s.pdf > 0.0f)) return s;
    s.weight = f * s.wi.z / s.pdf;
    s.valid = true;
    return s;
  }

 private:
  float k_schlick() const { return k_direct(roughness_); }
  // sample_ggx_vndf(wo, u, alpha).h (Heitz 2018, listing 1), without the pdf it also
  // computes (the sample's pdf comes from eval below).
  glm::vec3 vndf_half_vector(glm::vec2 u) const {
    const glm::vec3 wo = wo_;
    const float alpha = alpha_;
    const glm::vec3 Vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
    const glm::vec3 T1 = lensq > 0.0f ? glm::vec3(-Vh.y, Vh.x, 0.0f) / std::sqrt(lensq)
                                      : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 T2 = glm::cross(Vh, T1);
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    const float t1 = r * std::cos(phi);
    float t2 = r * std::sin(phi);
    const float s = 0.5f * (1.0f + Vh.z);
    t2 = (1.0f - s) * safe_sqrt(1.0f - t1 * t1) + s * t2;
    const glm::vec3 Nh = t1 * T1 + t2 * T2 + safe_sqrt(1.0f - t1 * t1 - t2 * t2) * Vh;
    return glm::normalize(glm::vec3(alpha * Nh.x, alpha * Nh.y, std::max(Nh.z, 1e-7f)));
  }
  // Brdf::specular_albedo.
  glm::vec3 specular_albedo(float mu) const {
    const glm::vec2 ab = table_->AB(mu, roughness_);
    glm::vec3 Es = F0_ * ab.x + ab.y;
    if (multiscatter_) Es += Fms_ * (1.0f - (ab.x + ab.y));
    return Es;
  }

  glm::vec3 wo_;
  glm::vec3 base_color_;
  float metallic_, roughness_, alpha_;
  glm::vec3 F0_;
  GeometryModel geometry_;
  bool multiscatter_;
  const EnergyTable* table_;
  float E_avg_ = 1.0f;
  glm::vec3 Fms_{0.0f};
  glm::vec3 Es_avg_{0.0f};
  // Per vertex.
  float p_spec_ = 1.0f;
  glm::vec3 lambert_{0.0f};
  float lambda_o_ = 0.0f, G1_o_ = 0.0f, schlick_o_ = 0.0f;
  glm::vec3 Es_o_{0.0f};
  float E_o_ = 0.0f;
};

}  // namespace pbrkit
