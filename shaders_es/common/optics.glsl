// optics.glsl - GLSL twin of src/optics.h (keep the two in step; the test
// tests/test_optics_twin.c compares them on a grid of inputs).
// i: unit direction of travel, n: unit normal facing the incoming ray,
// eta = n1 / n2.

vec3 snell_reflect(vec3 i, vec3 n)
{
    return i - 2.0 * dot(n, i) * n;
}

// Refracted direction in t; false and the mirror direction on total internal reflection.
bool snell_refract(vec3 i, vec3 n, float eta, out vec3 t)
{
    float c = -dot(n, i);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0) {
        t = snell_reflect(i, n);
        return false;
    }
    t = eta * i + (eta * c - sqrt(k)) * n;
    return true;
}

// Schlick reflectance from n1 into n2; uses the transmitted cosine when n1 > n2, 1 on TIR.
float snell_fresnel_schlick(float cos_i, float n1, float n2)
{
    float r0 = (n1 - n2) / (n1 + n2);
    float c = abs(cos_i);
    r0 *= r0;
    if (n1 > n2) {
        float eta = n1 / n2;
        float sin2_t = eta * eta * (1.0 - c * c);
        if (sin2_t >= 1.0) return 1.0;
        c = sqrt(1.0 - sin2_t);
    }
    float m = 1.0 - c;
    return r0 + (1.0 - r0) * m * m * m * m * m;
}

// Transmittance of a path of length d through a medium with coefficient sigma.
vec3 snell_beer_lambert(vec3 sigma, float d)
{
    return exp(-sigma * d);
}
