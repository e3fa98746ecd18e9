// The constants and scalar helpers every shader of the material model shares (brdf.glsl,
// iridescence.glsl and what includes them), so that neither includes the other for them.
const float kPi = 3.14159265358979323846;
const float kInvPi = 0.31830988618379067154;

float saturate(float x) { return clamp(x, 0.0, 1.0); }
