// SPDX-License-Identifier: MIT
/* mesh_gltf.cpp — glTF 2.0 loader (.gltf / .glb) on top of Debian's tinygltf.
 * The only C++ file of the library: every entry point catches all exceptions, and
 * every accessor is bounds-checked here before a byte of it is read. */
extern "C" {
#include "mesh/mesh.h"
}

#include <tiny_gltf.h> /* declarations only: the implementation is libtinygltf.so */

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <map>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

/* A loaded scene file: the frame lists and what they point to. */
#define SNELL__SCENE_NAME 64
struct snell_scene_file {
    snell_alloc alloc;
    int glass_count, opaque_count, mesh_count, has_camera;
    snell_glass glass[SNELL_MAX_GLASS];
    snell_opaque opaque[SNELL_MAX_OPAQUE];
    float glass_model[SNELL_MAX_GLASS][16];
    float opaque_model[SNELL_MAX_OPAQUE][16];
    snell_mesh *meshes[SNELL_MAX_GLASS + SNELL_MAX_OPAQUE]; /* owned: the ones the lists use */
    snell_camera camera;
    char glass_name[SNELL_MAX_GLASS][SNELL__SCENE_NAME];   /* glTF node names (snell_scene_file_glass_name) */
    char opaque_name[SNELL_MAX_OPAQUE][SNELL__SCENE_NAME];
    float centre[3], radius; /* bounding sphere of every object's world vertices (snell_scene_file_frame) */
};

namespace {

/* Inputs above 1 GiB are refused (tinygltf also takes lengths as unsigned int). */
const size_t kMaxInputBytes = size_t(1) << 30;
/* Node hierarchy guards: depth (a cycle shows up as unbounded depth) and the
 * number of mesh instances (shared subtrees can multiply exponentially). */
const int kMaxDepth = 256;
const size_t kMaxInstances = size_t(1) << 20;

struct LoadError {
    snell_status status;
    std::string msg;
};

[[noreturn]] void fail(snell_status st, const std::string &msg) { throw LoadError{st, msg}; }

/* --- filesystem callbacks -------------------------------------------------- */
/* Files are untrusted: a model's buffer and image URIs may name
 * files in its own folder only. Memory input must not touch the filesystem at
 * all: a URI naming a file is an error there. tinygltf percent-decodes a URI,
 * joins it to the base directory and asks FileExists/ReadWholeFile; it then
 * tries the URI relative to the current directory too, which the policy
 * never accepts. A candidate path is allowed when its real path (symlinks
 * resolved) is a regular file under the real path of the model's folder, and
 * the URI is not absolute; with SNELL_LOAD_ALLOW_OUTSIDE_FOLDER any regular
 * file is. Refusals are collected for the error message, which names the URI
 * and the reason, never the file's size. (A folder changed while it loads can
 * still race the check; the file is opened by its resolved path with
 * O_NOFOLLOW.) */
struct FsPolicy {
    bool allow_files;
    bool allow_outside;   /* SNELL_LOAD_ALLOW_OUTSIDE_FOLDER */
    std::string base_dir; /* as tinygltf joins it ("" = the current directory) */
    std::string root;     /* real path of the model's folder, ending in '/'; "" = unresolvable */
    size_t budget;        /* the context's memory budget */
    size_t used;          /* bytes counted against it: the parse estimate, external files read */
    std::string refused;  /* "'uri' reason; ..." */
    std::string limit;    /* set when an external file exceeds the budget */
};

const size_t kMaxUriInMessage = 160;

std::string shown_uri(const std::string &uri)
{
    std::string u = uri.size() > kMaxUriInMessage ? uri.substr(0, kMaxUriInMessage) + "..." : uri;
    for (char &c : u)
        if (static_cast<unsigned char>(c) < 0x20) c = '?';
    return u;
}

void refuse(FsPolicy *pol, const std::string &uri, const char *why)
{
    std::string item = "'" + shown_uri(uri) + "' (" + why + ")";
    if (pol->refused.find(item) != std::string::npos) return; /* FileExists, then ReadWholeFile */
    if (pol->refused.size() > 1024) return;
    if (!pol->refused.empty()) pol->refused += "; ";
    pol->refused += item;
}

/* The URI a candidate path was made from, or false for tinygltf's fallback
 * candidate relative to the current directory (not the model's folder). */
bool uri_of(const FsPolicy *pol, const std::string &path, std::string *uri)
{
    if (pol->base_dir.empty()) {
        *uri = path;
        return true;
    }
    const std::string &prefix = pol->base_dir; /* ends in '/' (snell_mesh_load_gltf_ex) */
    if (path.compare(0, prefix.size(), prefix) == 0) {
        *uri = path.substr(prefix.size());
        return true;
    }
    if (pol->allow_outside && !path.empty() && path[0] == '/') { /* an absolute URI, fs_expand */
        *uri = path;
        return true;
    }
    return false;
}

/* Resolves a candidate path; true and its real path if the policy allows it. */
bool allowed(FsPolicy *pol, const std::string &path, std::string *real)
{
    std::string uri;
    if (!pol->allow_files || !uri_of(pol, path, &uri)) return false;
    if (uri.find('\0') != std::string::npos) {
        refuse(pol, uri, "contains a NUL byte");
        return false;
    }
    if (!pol->allow_outside && !uri.empty() && uri[0] == '/') {
        refuse(pol, uri, "is an absolute path");
        return false;
    }
    char *rp = realpath(path.c_str(), nullptr);
    if (!rp) return false; /* absent: tinygltf reports "File not found" */
    *real = rp;
    std::free(rp);
    struct stat sb;
    if (stat(real->c_str(), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        refuse(pol, uri, "is not a regular file");
        return false;
    }
    if (!pol->allow_outside && (pol->root.empty() || real->compare(0, pol->root.size(), pol->root) != 0)) {
        refuse(pol, uri, "leaves the model's folder");
        return false;
    }
    return true;
}

bool fs_exists(const std::string &path, void *user)
{
    std::string real;
    return allowed(static_cast<FsPolicy *>(user), path, &real);
}

/* No ~ or $VAR expansion. tinygltf joins even an absolute URI to the base
 * directory ("dir//abs"); with SNELL_LOAD_ALLOW_OUTSIDE_FOLDER it names the
 * absolute path, as the caller allowed. */
std::string fs_expand(const std::string &path, void *user)
{
    const FsPolicy *pol = static_cast<const FsPolicy *>(user);
    std::string uri;
    if (pol->allow_files && pol->allow_outside && uri_of(pol, path, &uri) && !uri.empty() && uri[0] == '/') return uri;
    return path;
}

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    FsPolicy *pol = static_cast<FsPolicy *>(user);
    std::string real;
    if (!pol->allow_files) {
        if (err) *err += "external file '" + shown_uri(path) + "' referenced from in-memory glTF\n";
        return false;
    }
    if (!allowed(pol, path, &real)) {
        if (err) *err += "refused\n";
        return false;
    }
    int opened;
    const char *why;
    int fd = snell__open_regular_nofollow(real.c_str(), &opened, &why);
    struct stat sb;
    if (fd < 0 || fstat(fd, &sb) != 0) {
        if (fd >= 0) close(fd);
        if (err) *err += "cannot open '" + shown_uri(path) + "': " + (fd < 0 ? why : std::strerror(errno)) + "\n";
        return false;
    }
    size_t size = static_cast<size_t>(sb.st_size);
    if (static_cast<unsigned long long>(sb.st_size) > kMaxInputBytes ||
        size > pol->budget - std::min(pol->used, pol->budget)) {
        close(fd);
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "'%s' (%.1f MiB) would exceed the memory budget of %.1f MiB (snell_ctx_desc.memory_budget)",
                      shown_uri(path).c_str(), static_cast<double>(size) / 1048576.0,
                      static_cast<double>(pol->budget) / 1048576.0);
        if (pol->limit.empty()) pol->limit = buf;
        if (err) *err += std::string(buf) + "\n";
        return false;
    }
    pol->used += size;
    out->resize(size);
    size_t got = 0;
    while (got < size) {
        ssize_t n = read(fd, out->data() + got, size - got);
        if (n <= 0) break;
        got += static_cast<size_t>(n);
    }
    close(fd);
    if (got != size) {
        if (err) *err += "short read on '" + shown_uri(path) + "'\n";
        return false;
    }
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err) *err += "writing is not supported\n";
    return false;
}

/* Images are irrelevant for geometry: skip decoding them (and stb_image's
 * attack surface) entirely. */
bool skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *,
                int, void *)
{
    return true;
}

/* --- accessor validation --------------------------------------------------- */
struct View {
    const unsigned char *base; /* first element */
    size_t stride, count, elem_size;
    int component_type;
};

size_t component_size(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

bool add_ok(size_t a, size_t b, size_t *r)
{
    if (a > SIZE_MAX - b) return false;
    *r = a + b;
    return true;
}

/* Resolves accessor idx into a bounds-checked strided view. what names it in
 * errors. type is the required TINYGLTF_TYPE_*; index accessors pass
 * is_index to allow the three unsigned integer component types. */
View get_view(const tinygltf::Model &m, int idx, int type, bool is_index, const char *what)
{
    char buf[256];
    if (idx < 0 || static_cast<size_t>(idx) >= m.accessors.size()) {
        std::snprintf(buf, sizeof buf, "%s accessor %d does not exist (%zu accessors)", what, idx,
                      m.accessors.size());
        fail(SNELL_E_PARSE, buf);
    }
    const tinygltf::Accessor &a = m.accessors[static_cast<size_t>(idx)];
    if (a.sparse.isSparse) {
        std::snprintf(buf, sizeof buf, "%s accessor %d is sparse (not supported)", what, idx);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (a.type != type) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has type %d, expected %d", what, idx, a.type, type);
        fail(SNELL_E_PARSE, buf);
    }
    if (is_index) {
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            std::snprintf(buf, sizeof buf, "%s accessor %d has component type %d, expected an unsigned integer",
                          what, idx, a.componentType);
            fail(SNELL_E_PARSE, buf);
        }
    } else if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        /* KHR_mesh_quantization (integer positions/normals) is not supported */
        std::snprintf(buf, sizeof buf, "%s accessor %d has component type %d, only FLOAT is supported", what,
                      idx, a.componentType);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (a.count > SNELL_MESH_MAX_VERTICES * size_t(3)) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has %zu elements (limit %zu)", what, idx, a.count,
                      SNELL_MESH_MAX_VERTICES * size_t(3));
        fail(SNELL_E_LIMIT, buf);
    }
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has no valid bufferView (%d)", what, idx, a.bufferView);
        fail(SNELL_E_PARSE, buf);
    }
    const tinygltf::BufferView &bv = m.bufferViews[static_cast<size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size()) {
        std::snprintf(buf, sizeof buf, "bufferView %d references missing buffer %d", a.bufferView, bv.buffer);
        fail(SNELL_E_PARSE, buf);
    }
    const std::vector<unsigned char> &data = m.buffers[static_cast<size_t>(bv.buffer)].data;
    size_t view_end;
    if (!add_ok(bv.byteOffset, bv.byteLength, &view_end) || view_end > data.size()) {
        std::snprintf(buf, sizeof buf, "bufferView %d (offset %zu, length %zu) exceeds buffer %d of %zu bytes",
                      a.bufferView, bv.byteOffset, bv.byteLength, bv.buffer, data.size());
        fail(SNELL_E_PARSE, buf);
    }
    const size_t csize = component_size(a.componentType);
    const size_t ncomp = type == TINYGLTF_TYPE_SCALAR ? 1 : 3;
    const size_t elem = csize * ncomp;
    size_t stride = bv.byteStride ? bv.byteStride : elem;
    /* glTF: byteStride is 4..252 and a multiple of the component size; it must
     * at least cover one element or elements would overlap. */
    if (bv.byteStride && (bv.byteStride < elem || bv.byteStride > 252 || bv.byteStride % csize != 0)) {
        std::snprintf(buf, sizeof buf, "bufferView %d has invalid byteStride %zu for %s elements of %zu bytes",
                      a.bufferView, bv.byteStride, what, elem);
        fail(SNELL_E_PARSE, buf);
    }
    size_t need = 0;
    if (a.count > 0) {
        /* byteOffset + stride * (count - 1) + elem <= byteLength, overflow-checked */
        if ((a.count - 1) > (SIZE_MAX - elem) / stride || !add_ok(a.byteOffset, (a.count - 1) * stride + elem, &need) ||
            need > bv.byteLength) {
            std::snprintf(buf, sizeof buf,
                          "%s accessor %d (offset %zu, %zu x %zu bytes, stride %zu) exceeds bufferView %d of %zu bytes",
                          what, idx, a.byteOffset, a.count, elem, stride, a.bufferView, bv.byteLength);
            fail(SNELL_E_PARSE, buf);
        }
    }
    View v;
    v.base = data.data() + bv.byteOffset + a.byteOffset;
    v.stride = stride;
    v.count = a.count;
    v.elem_size = elem;
    v.component_type = a.componentType;
    return v;
}

void read_vec3(const View &v, size_t i, float out[3]) { std::memcpy(out, v.base + i * v.stride, 12); }

uint32_t read_index(const View &v, size_t i)
{
    const unsigned char *p = v.base + i * v.stride;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t s;
        std::memcpy(&s, p, 2);
        return s;
    }
    default: {
        uint32_t u;
        std::memcpy(&u, p, 4);
        return u;
    }
    }
}

/* --- transforms (column-major 4x4, doubles) -------------------------------- */
struct Mat4 {
    double m[16];
};

Mat4 identity()
{
    Mat4 r;
    for (int i = 0; i < 16; i++) r.m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    return r;
}

Mat4 mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

void check_finite(const std::vector<double> &v, int node, const char *what)
{
    for (double d : v)
        if (!std::isfinite(d)) {
            char buf[128];
            std::snprintf(buf, sizeof buf, "node %d: %s has a non-finite value", node, what);
            fail(SNELL_E_PARSE, buf);
        }
}

/* Local transform of a node: matrix if given, else T * R * S (glTF 2.0 §5.25). */
Mat4 local_transform(const tinygltf::Node &n, int idx)
{
    char buf[128];
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16) {
            std::snprintf(buf, sizeof buf, "node %d: matrix has %zu elements, expected 16", idx, n.matrix.size());
            fail(SNELL_E_PARSE, buf);
        }
        check_finite(n.matrix, idx, "matrix");
        Mat4 r;
        for (int i = 0; i < 16; i++) r.m[i] = n.matrix[static_cast<size_t>(i)];
        /* glTF 2.0 §5.25: a node's matrix is a TRS transform; a projective
         * bottom row would shear and project the glass */
        if (std::fabs(r.m[3]) > 1e-6 || std::fabs(r.m[7]) > 1e-6 || std::fabs(r.m[11]) > 1e-6 ||
            std::fabs(r.m[15] - 1.0) > 1e-6) {
            std::snprintf(buf, sizeof buf, "node %d: matrix is not affine (bottom row %g %g %g %g, want 0 0 0 1)", idx,
                          r.m[3], r.m[7], r.m[11], r.m[15]);
            fail(SNELL_E_PARSE, buf);
        }
        return r;
    }
    if ((!n.translation.empty() && n.translation.size() != 3) || (!n.scale.empty() && n.scale.size() != 3) ||
        (!n.rotation.empty() && n.rotation.size() != 4)) {
        std::snprintf(buf, sizeof buf, "node %d: translation/rotation/scale has the wrong number of elements", idx);
        fail(SNELL_E_PARSE, buf);
    }
    check_finite(n.translation, idx, "translation");
    check_finite(n.rotation, idx, "rotation");
    check_finite(n.scale, idx, "scale");
    Mat4 t = identity(), r = identity(), s = identity();
    if (!n.translation.empty())
        for (int i = 0; i < 3; i++) t.m[12 + i] = n.translation[static_cast<size_t>(i)];
    if (!n.scale.empty())
        for (int i = 0; i < 3; i++) s.m[i * 5] = n.scale[static_cast<size_t>(i)];
    if (!n.rotation.empty()) {
        /* unit quaternion (x, y, z, w); normalised here to tolerate rounding */
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(len > 0.0)) {
            std::snprintf(buf, sizeof buf, "node %d: rotation quaternion is zero", idx);
            fail(SNELL_E_PARSE, buf);
        }
        x /= len; y /= len; z /= len; w /= len;
        r.m[0] = 1 - 2 * (y * y + z * z); r.m[4] = 2 * (x * y - z * w);     r.m[8] = 2 * (x * z + y * w);
        r.m[1] = 2 * (x * y + z * w);     r.m[5] = 1 - 2 * (x * x + z * z); r.m[9] = 2 * (y * z - x * w);
        r.m[2] = 2 * (x * z - y * w);     r.m[6] = 2 * (y * z + x * w);     r.m[10] = 1 - 2 * (x * x + y * y);
    }
    return mul(t, mul(r, s));
}

/* --- the node tree -------------------------------------------------------- */
/* What a walk of the node tree hands each node instance: the node and its
 * world transform (its parents' times its own), its mesh checked to exist. */
struct NodeVisitor {
    virtual void node(int idx, const tinygltf::Node &n, const Mat4 &world) = 0;
    virtual ~NodeVisitor() {}
};

/* Roots to draw: the default scene, else scene 0, else every node that is
 * nobody's child. */
std::vector<int> scene_roots(const tinygltf::Model &m)
{
    if (!m.scenes.empty()) {
        size_t s = (m.defaultScene >= 0 && static_cast<size_t>(m.defaultScene) < m.scenes.size())
                       ? static_cast<size_t>(m.defaultScene) : 0;
        return m.scenes[s].nodes;
    }
    std::vector<char> is_child(m.nodes.size(), 0);
    for (const tinygltf::Node &n : m.nodes)
        for (int c : n.children)
            if (c >= 0 && static_cast<size_t>(c) < m.nodes.size()) is_child[static_cast<size_t>(c)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m.nodes.size(); i++)
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    return roots;
}

void walk_node(const tinygltf::Model &model, NodeVisitor &v, int node, const Mat4 &parent, int depth,
               size_t *instances)
{
    char buf[160];
    if (node < 0 || static_cast<size_t>(node) >= model.nodes.size()) {
        std::snprintf(buf, sizeof buf, "node %d does not exist (%zu nodes)", node, model.nodes.size());
        fail(SNELL_E_PARSE, buf);
    }
    if (depth > kMaxDepth) {
        std::snprintf(buf, sizeof buf, "node hierarchy deeper than %d at node %d (cycle?)", kMaxDepth, node);
        fail(SNELL_E_PARSE, buf);
    }
    if (++*instances > kMaxInstances) {
        std::snprintf(buf, sizeof buf, "more than %zu node instances", kMaxInstances);
        fail(SNELL_E_LIMIT, buf);
    }
    const tinygltf::Node &n = model.nodes[static_cast<size_t>(node)];
    Mat4 world = mul(parent, local_transform(n, node));
    if (n.mesh >= 0 && static_cast<size_t>(n.mesh) >= model.meshes.size()) {
        std::snprintf(buf, sizeof buf, "node %d references missing mesh %d", node, n.mesh);
        fail(SNELL_E_PARSE, buf);
    }
    v.node(node, n, world);
    for (int c : n.children) walk_node(model, v, c, world, depth + 1, instances);
}

/* Every node instance of the scene to draw, depth first in glTF's order;
 * the depth and the instances are bounded (kMaxDepth, kMaxInstances). */
void walk_nodes(const tinygltf::Model &model, NodeVisitor &v)
{
    size_t instances = 0;
    for (int r : scene_roots(model)) walk_node(model, v, r, identity(), 0, &instances);
}

/* --- geometry accumulation -------------------------------------------------- */
struct Builder : NodeVisitor {
    const tinygltf::Model &model;
    snell_ctx *ctx;
    std::vector<float> pos, nrm;
    std::vector<uint32_t> idx;
    bool logged_no_surface = false;
    Builder(const tinygltf::Model &m, snell_ctx *c) : model(m), ctx(c) {}

    void add_primitive(const tinygltf::Primitive &p, const Mat4 &M, int mesh_idx);
    void node(int idx, const tinygltf::Node &n, const Mat4 &world) override;
};

void Builder::add_primitive(const tinygltf::Primitive &p, const Mat4 &M, int mesh_idx)
{
    char buf[256];
    if (p.mode < TINYGLTF_MODE_POINTS || p.mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        std::snprintf(buf, sizeof buf, "mesh %d: primitive mode %d is not a glTF mode (0..6)", mesh_idx, p.mode);
        fail(SNELL_E_PARSE, buf);
    }
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        /* points and lines have no surface: left out, and said once a file */
        if (!logged_no_surface)
            snell__log(ctx, SNELL_LOG_WARN, "glTF: mesh %d: a primitive of points or lines (mode %d) left out: no surface",
                       mesh_idx, p.mode);
        logged_no_surface = true;
        return;
    }
    auto pit = p.attributes.find("POSITION");
    if (pit == p.attributes.end()) return; /* nothing to draw */
    View vp = get_view(model, pit->second, TINYGLTF_TYPE_VEC3, false, "POSITION");
    auto nit = p.attributes.find("NORMAL");
    bool has_n = nit != p.attributes.end();
    View vn = has_n ? get_view(model, nit->second, TINYGLTF_TYPE_VEC3, false, "NORMAL") : View();
    if (has_n && vn.count != vp.count) {
        std::snprintf(buf, sizeof buf, "mesh %d: NORMAL has %zu elements, POSITION %zu", mesh_idx, vn.count,
                      vp.count);
        fail(SNELL_E_PARSE, buf);
    }
    /* corner list (local vertex ids) */
    if (p.indices < -1) { /* tinygltf uses -1 for "absent"; anything lower is invalid */
        std::snprintf(buf, sizeof buf, "mesh %d: indices accessor %d does not exist", mesh_idx, p.indices);
        fail(SNELL_E_PARSE, buf);
    }
    std::vector<uint32_t> corners;
    size_t ncorner = vp.count;
    View vi;
    if (p.indices >= 0) {
        vi = get_view(model, p.indices, TINYGLTF_TYPE_SCALAR, true, "indices");
        ncorner = vi.count;
    }
    corners.resize(ncorner);
    for (size_t i = 0; i < ncorner; i++) {
        uint32_t v = p.indices >= 0 ? read_index(vi, i) : static_cast<uint32_t>(i);
        if (v >= vp.count) {
            std::snprintf(buf, sizeof buf, "mesh %d: index %u at position %zu is out of range (%zu vertices)",
                          mesh_idx, v, i, vp.count);
            fail(SNELL_E_PARSE, buf);
        }
        corners[i] = v;
    }
    /* triangles (glTF 2.0 §3.7.2.1 topology rules); trailing corners that do not
     * make a whole triangle are ignored */
    std::vector<uint32_t> tris;
    if (p.mode == TINYGLTF_MODE_TRIANGLES) {
        tris.assign(corners.begin(), corners.begin() + static_cast<std::ptrdiff_t>(ncorner / 3 * 3));
    } else if (ncorner >= 3) {
        tris.reserve(3 * (ncorner - 2));
        for (size_t i = 0; i + 2 < ncorner; i++) {
            if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                /* every other triangle is flipped to keep the winding */
                tris.push_back(corners[i]);
                tris.push_back(corners[i + 1 + (i & 1)]);
                tris.push_back(corners[i + 2 - (i & 1)]);
            } else {
                tris.push_back(corners[0]);
                tris.push_back(corners[i + 1]);
                tris.push_back(corners[i + 2]);
            }
        }
    }
    if (tris.empty()) return;
    if (pos.size() / 3 + vp.count > SNELL_MESH_MAX_VERTICES || (idx.size() + tris.size()) / 3 > SNELL_MESH_MAX_TRIANGLES) {
        std::snprintf(buf, sizeof buf, "scene exceeds %u vertices or %u triangles", SNELL_MESH_MAX_VERTICES,
                      SNELL_MESH_MAX_TRIANGLES);
        fail(SNELL_E_LIMIT, buf);
    }
    {
        /* positions + normals + indices, twice: the mesh's own arrays are
         * copied from these (a shared subtree instanced many times grows
         * them without the file growing) */
        size_t bytes = 2 * (8 * (pos.size() + 3 * vp.count) + 4 * (idx.size() + tris.size()));
        snell_status st = snell__budget_check(ctx, bytes, "the scene's vertex and index arrays");
        if (st != SNELL_OK) fail(st, snell_last_error(ctx));
    }
    /* Normals transform by the inverse transpose of the upper 3x3, which is the
     * cofactor matrix divided by the determinant; only the direction matters,
     * so the cofactor matrix times sign(det) does. */
    const double *m = M.m;
    double cof[9] = {
        m[5] * m[10] - m[6] * m[9], m[6] * m[8] - m[4] * m[10], m[4] * m[9] - m[5] * m[8],
        m[9] * m[2] - m[10] * m[1], m[10] * m[0] - m[8] * m[2], m[8] * m[1] - m[9] * m[0],
        m[1] * m[6] - m[2] * m[5],  m[2] * m[4] - m[0] * m[6],  m[0] * m[5] - m[1] * m[4]};
    /* cof[3*c + r]: column c of the cofactor matrix, i.e. cofactor of m(r, c) */
    double det = m[0] * cof[0] + m[4] * cof[3] + m[8] * cof[6];
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return; /* zero scale hides the instance */
    double sg = det > 0 ? 1.0 : -1.0;
    size_t base = pos.size() / 3;
    pos.resize(pos.size() + 3 * vp.count);
    nrm.resize(nrm.size() + 3 * vp.count);
    bool need_smooth = !has_n;
    for (size_t i = 0; i < vp.count; i++) {
        float p3[3];
        read_vec3(vp, i, p3);
        for (int r = 0; r < 3; r++) {
            double w = m[r] * p3[0] + m[4 + r] * p3[1] + m[8 + r] * p3[2] + m[12 + r];
            if (!std::isfinite(w) || std::fabs(w) > 3.0e38) {
                std::snprintf(buf, sizeof buf, "mesh %d: vertex %zu is not finite after the node transform", mesh_idx, i);
                fail(SNELL_E_PARSE, buf);
            }
            pos[3 * (base + i) + static_cast<size_t>(r)] = static_cast<float>(w);
        }
        if (has_n) {
            float n3[3];
            read_vec3(vn, i, n3);
            double o[3];
            /* inverse transpose = cof (as a matrix applied to n, rows of cof^T) */
            for (int r = 0; r < 3; r++) o[r] = sg * (cof[r] * n3[0] + cof[3 + r] * n3[1] + cof[6 + r] * n3[2]);
            double len = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            if (len > 1e-30 && std::isfinite(len)) {
                for (int r = 0; r < 3; r++) nrm[3 * (base + i) + static_cast<size_t>(r)] = static_cast<float>(o[r] / len);
            } else {
                need_smooth = true; /* zero or NaN normal in the file: recompute */
            }
        }
    }
    /* A mirroring transform (det < 0) turns counter-clockwise into clockwise;
     * glTF says the winding then flips, so swap two corners to keep CCW. */
    if (det < 0)
        for (size_t t = 0; t + 2 < tris.size(); t += 3) std::swap(tris[t + 1], tris[t + 2]);
    if (need_smooth) {
        std::vector<float> sm(3 * vp.count);
        snell__mesh_compute_normals(&pos[3 * base], tris.data(), static_cast<uint32_t>(vp.count),
                                    static_cast<uint32_t>(tris.size() / 3), sm.data());
        for (size_t i = 0; i < vp.count; i++) {
            float *d = &nrm[3 * (base + i)];
            if (!has_n || !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0.5f)) std::memcpy(d, &sm[3 * i], 12);
        }
    }
    /* push_back grows the array geometrically; a reserve of exactly what
     * this primitive adds would reallocate (and copy) the whole array on
     * every instance: quadratic in the instances */
    for (uint32_t c : tris) idx.push_back(static_cast<uint32_t>(base + c));
}

void Builder::node(int, const tinygltf::Node &n, const Mat4 &world)
{
    if (n.mesh < 0) return;
    for (const tinygltf::Primitive &p : model.meshes[static_cast<size_t>(n.mesh)].primitives)
        add_primitive(p, world, n.mesh);
}

/* tinygltf and nlohmann::json convert nested JSON (e.g. "extras") recursively,
 * so deeply nested input overflows the stack: a 200000-deep array segfaulted
 * in testing. Measure the nesting depth first (brackets outside strings).
 * Returns about how many values the JSON holds (commas and opening brackets
 * outside strings), which the parse's memory grows with. */
size_t check_json_depth(const unsigned char *s, size_t n)
{
    const size_t kMaxJsonDepth = 512; /* real glTF files stay below ~20 */
    size_t depth = 0, values = 1;
    bool in_str = false;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = s[i];
        if (in_str) {
            if (c == '\\') i++;
            else if (c == '"') in_str = false;
        } else if (c == '"') {
            in_str = true;
        } else if (c == '[' || c == '{') {
            values++;
            if (++depth > kMaxJsonDepth) fail(SNELL_E_LIMIT, "JSON nested deeper than 512 levels");
        } else if ((c == ']' || c == '}') && depth > 0) {
            depth--;
        } else if (c == ',') {
            values++;
        }
    }
    return values;
}

/* GLB container check before tinygltf sees it: the 12-byte header, a JSON
 * chunk first, and every chunk's 8-byte header and data inside both the
 * header's length and the buffer (tinygltf 2.7 checks the BIN chunk's data
 * without its header and so copies up to 8 bytes past the buffer). */
void check_glb(const unsigned char *d, size_t size)
{
    char buf[160];
    uint32_t version, length, clen, ctype;
    if (size < 20) fail(SNELL_E_PARSE, "GLB: truncated header");
    std::memcpy(&version, d + 4, 4);
    std::memcpy(&length, d + 8, 4);
    std::memcpy(&clen, d + 12, 4);
    std::memcpy(&ctype, d + 16, 4);
    if (version != 2) {
        std::snprintf(buf, sizeof buf, "GLB: version %u, only 2 is supported", version);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (length > size || length < 20) {
        std::snprintf(buf, sizeof buf, "GLB: header says %u bytes, have %zu (truncated?)", length, size);
        fail(SNELL_E_PARSE, buf);
    }
    if (ctype != 0x4E4F534Au /* "JSON" */ || clen > length - 20) {
        std::snprintf(buf, sizeof buf, "GLB: bad JSON chunk (type 0x%08x, %u bytes)", ctype, clen);
        fail(SNELL_E_PARSE, buf);
    }
    for (size_t off = 12; off < length;) {
        if (length - off < 8) {
            std::snprintf(buf, sizeof buf, "GLB: chunk header at byte %zu runs past the end (%u bytes)", off, length);
            fail(SNELL_E_PARSE, buf);
        }
        std::memcpy(&clen, d + off, 4);
        if (clen > length - off - 8) {
            std::snprintf(buf, sizeof buf, "GLB: chunk at byte %zu says %u bytes, only %zu follow its header", off,
                          clen, length - off - 8);
            fail(SNELL_E_PARSE, buf);
        }
        off += 8 + static_cast<size_t>(clen);
    }
}

/* Required extensions that do not change the geometry this loader reads
 * (materials, textures, lights): a file requiring them still loads. Any other
 * required extension is an error naming it (glTF 2.0 §3.12: a loader that
 * does not support a required extension must not load the file). */
bool extension_tolerated(const std::string &e)
{
    static const char *const known[] = {"KHR_texture_transform", "KHR_texture_basisu", "EXT_texture_webp",
                                        "EXT_texture_avif", "KHR_lights_punctual", "KHR_materials_variants"};
    if (e.compare(0, 14, "KHR_materials_") == 0) return true;
    for (const char *k : known)
        if (e == k) return true;
    return false;
}

/* asset.version and extensionsRequired: tinygltf 2.7 parses both before any
 * buffer, so they are set even when it fails later (a glTF 1.0 file fails on
 * its object-shaped sections, a Draco file on accessors without a
 * bufferView): these messages replace the misleading ones. */
void check_version_and_extensions(const tinygltf::Model &model)
{
    const std::string &v = model.asset.version;
    if (!v.empty() && v.compare(0, 2, "2.") != 0) {
        if (v[0] == '1' || v[0] == '0')
            fail(SNELL_E_UNSUPPORTED, "glTF 1.0 is not supported (asset.version \"" + shown_uri(v) +
                                          "\"): convert the file to glTF 2.0");
        fail(SNELL_E_UNSUPPORTED, "glTF version \"" + shown_uri(v) + "\" is not supported (2.x only)");
    }
    std::string bad;
    for (const std::string &e : model.extensionsRequired) {
        if (extension_tolerated(e)) continue;
        if (!bad.empty()) bad += ", ";
        bad += shown_uri(e);
        if (e == "KHR_draco_mesh_compression") bad += " (Draco-compressed geometry)";
        else if (e == "EXT_meshopt_compression") bad += " (meshoptimizer-compressed buffers)";
        else if (e == "KHR_mesh_quantization") bad += " (integer vertex attributes)";
    }
    if (!bad.empty()) fail(SNELL_E_UNSUPPORTED, "the file requires extensions that are not supported: " + bad);
}

/* tinygltf's peak memory for an input: its JSON DOM and the copies it makes
 * of data: URIs (the base64 text, its decoded string, the buffer) cost about
 * 6 bytes per byte of JSON (measured: 28 MB of JSON with one data: URI peaked
 * at 164 MB resident); 8 leaves room. A GLB's BIN chunk is copied once more
 * into the buffer. Checked against the budget before parsing. */
const size_t kJsonMemFactor = 8;
/* Every JSON value costs a DOM node and a tinygltf::Value (where it lands in
 * "extras", a map or vector entry besides), whatever its text's length: a
 * long array of one-digit numbers costs many times the byte factor a byte. */
const size_t kJsonValueBytes = 256;

void check_parse_budget(snell_ctx *ctx, size_t json_bytes, size_t bin_bytes, size_t values, FsPolicy *pol)
{
    char what[200];
    double d = static_cast<double>(kJsonMemFactor) * static_cast<double>(json_bytes) + 2.0 * static_cast<double>(bin_bytes) +
               static_cast<double>(kJsonValueBytes) * static_cast<double>(values);
    size_t est = d >= 1.8e19 ? SIZE_MAX : static_cast<size_t>(d);
    pol->used = est;
    if (est <= pol->budget) return;
    std::snprintf(what, sizeof what,
                  "parsing %zu bytes of JSON (about %zu values; data: URIs included) and %zu of binary chunk",
                  json_bytes, values, bin_bytes);
    snell_status st = snell__budget_check(ctx, est, what);
    fail(st, snell_last_error(ctx));
}

/* Parses and checks a glTF 2.0 file in memory into model (throws LoadError). */
void parse(snell_ctx *ctx, const unsigned char *data, size_t size, const std::string &base_dir, bool allow_files,
           unsigned flags, tinygltf::Model &model)
{
    if (size > kMaxInputBytes) fail(SNELL_E_LIMIT, "glTF input larger than 1 GiB");
    tinygltf::TinyGLTF loader;
    FsPolicy pol;
    pol.allow_files = allow_files;
    pol.allow_outside = (flags & SNELL_LOAD_ALLOW_OUTSIDE_FOLDER) != 0;
    pol.base_dir = base_dir;
    pol.budget = snell__ctx_budget(ctx);
    pol.used = 0;
    if (allow_files) {
        char *rp = realpath(base_dir.empty() ? "." : base_dir.c_str(), nullptr);
        if (rp) {
            pol.root = rp;
            std::free(rp);
            if (pol.root.back() != '/') pol.root += '/';
        }
    }
    tinygltf::FsCallbacks fs = {fs_exists, fs_expand, fs_read, fs_write, &pol};
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(skip_image, nullptr);
    std::string err, warn;
    bool ok;
    bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    if (glb) {
        check_glb(data, size);
        uint32_t jlen;
        std::memcpy(&jlen, data + 12, 4);
        size_t values = check_json_depth(data + 20, jlen);
        check_parse_budget(ctx, jlen, size - 20 - jlen, values, &pol);
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(size), base_dir);
    } else {
        size_t values = check_json_depth(data, size);
        check_parse_budget(ctx, size, 0, values, &pol);
        ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char *>(data),
                                        static_cast<unsigned int>(size), base_dir);
    }
    check_version_and_extensions(model);
    if (!pol.limit.empty()) fail(SNELL_E_LIMIT, pol.limit);
    if (!ok && !pol.refused.empty())
        fail(SNELL_E_IO, "refused to read " + pol.refused +
                             ": URIs may name regular files in the model's folder only "
                             "(SNELL_LOAD_ALLOW_OUTSIDE_FOLDER lifts the folder rule)");
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        fail(SNELL_E_PARSE, "tinygltf: " + (err.empty() ? std::string("unknown error") : err));
    }
    if (!pol.refused.empty()) /* only images can be refused without failing the load */
        snell__log(ctx, SNELL_LOG_WARN, "glTF: image files not read: %s", pol.refused.c_str());
}

/* The builder's triangles as a mesh (the arrays copied into the context's allocator). */
snell_status adopt(snell_ctx *ctx, const Builder &b, snell_mesh **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    size_t nv = b.pos.size() / 3, nt = b.idx.size() / 3;
    float *pos = static_cast<float *>(snell__calloc(al, 3 * nv, sizeof(float)));
    float *nrm = static_cast<float *>(snell__calloc(al, 3 * nv, sizeof(float)));
    uint32_t *idx = static_cast<uint32_t *>(snell__calloc(al, 3 * nt, sizeof(uint32_t)));
    if (!pos || !nrm || !idx) {
        snell__free(al, pos);
        snell__free(al, nrm);
        snell__free(al, idx);
        fail(SNELL_E_NOMEM, "out of memory for the mesh");
    }
    std::memcpy(pos, b.pos.data(), 3 * nv * sizeof(float));
    std::memcpy(nrm, b.nrm.data(), 3 * nv * sizeof(float));
    std::memcpy(idx, b.idx.data(), 3 * nt * sizeof(uint32_t));
    return snell__mesh_adopt(ctx, al, pos, nrm, idx, static_cast<uint32_t>(nv), static_cast<uint32_t>(nt), out);
}

snell_status load(snell_ctx *ctx, const unsigned char *data, size_t size, const std::string &base_dir,
                  bool allow_files, unsigned flags, snell_mesh **out)
{
    try {
        tinygltf::Model model;
        parse(ctx, data, size, base_dir, allow_files, flags, model);
        Builder b(model, ctx);
        walk_nodes(model, b);
        if (b.idx.empty()) fail(SNELL_E_PARSE, "no triangle primitives in the scene");
        return adopt(ctx, b, out);
    } catch (const LoadError &e) {
        return snell__fail(ctx, e.status, "glTF: %s", e.msg.c_str());
    } catch (const std::bad_alloc &) {
        return snell__fail(ctx, SNELL_E_NOMEM, "glTF: out of memory");
    } catch (const std::exception &e) {
        return snell__fail(ctx, SNELL_E_PARSE, "glTF: %s", e.what());
    } catch (...) {
        return snell__fail(ctx, SNELL_E_PARSE, "glTF: unexpected exception");
    }
}

/* --- scene files (snell_scene_load_gltf) ----------------------------------- */
/* Thin-walled glass (KHR_materials_transmission without KHR_materials_volume,
 * or with thicknessFactor 0) is infinitely thin in glTF; the renderer's thin
 * wall needs a thickness, so it gets one too small to absorb or displace
 * anything visible (world units). */
const float kThinWall = 1e-4f;

/* Material extensions the scene loader reads; other KHR_materials_* ones are
 * logged once per file and ignored (an error when required). */
bool scene_extension_known(const std::string &e)
{
    return e == "KHR_materials_transmission" || e == "KHR_materials_ior" || e == "KHR_materials_volume" ||
           e == "KHR_materials_dispersion";
}

double number_or(const tinygltf::Value &obj, const char *key, double def)
{
    if (!obj.IsObject() || !obj.Has(key)) return def;
    const tinygltf::Value &v = obj.Get(key);
    if (!v.IsNumber()) fail(SNELL_E_PARSE, std::string("material extension field \"") + key + "\" is not a number");
    double d = v.GetNumberAsDouble();
    if (!std::isfinite(d)) fail(SNELL_E_PARSE, std::string("material extension field \"") + key + "\" is not finite");
    return d;
}

/* An opaque node instance of a primitive, kept until the lists are filled:
 * beyond SNELL_MAX_OPAQUE they are merged per colour (finish()). */
struct OpaqueInstance {
    snell_mesh *mesh;
    const tinygltf::Primitive *prim;
    int mesh_idx, node, material;
    float color[3];
    Mat4 world;
};

/* A glTF node's name as shown in stats: at most SNELL__SCENE_NAME - 1 bytes
 * (cut before a UTF-8 continuation byte), control characters as '?';
 * "node N" when it has none. */
void copy_name(const std::string &n, char *out)
{
    size_t len = std::min(n.size(), static_cast<size_t>(SNELL__SCENE_NAME - 1));
    while (len > 0 && len < n.size() && (static_cast<unsigned char>(n[len]) & 0xC0) == 0x80) len--;
    for (size_t i = 0; i < len; i++) out[i] = static_cast<unsigned char>(n[i]) < 0x20 || n[i] == 0x7f ? '?' : n[i];
    out[len] = '\0';
}

void node_name(const tinygltf::Model &model, int node, char *out)
{
    const std::string &n = model.nodes[static_cast<size_t>(node)].name;
    copy_name(n.empty() ? "node " + std::to_string(node) : n, out);
}

struct SceneBuilder : NodeVisitor {
    const tinygltf::Model &model;
    snell_ctx *ctx;
    snell_scene_file *out;
    std::map<std::pair<int, int>, snell_mesh *> meshes; /* (mesh, primitive) -> its mesh, shared by instances */
    std::vector<snell_mesh *> owned;                    /* every mesh made, until finish() hands them over */
    std::vector<OpaqueInstance> opaque;
    int glass_total = 0;                                /* glass instances, counted past the limit */
    std::string ignored;                                /* extensions ignored, for one log line */
    int camera_node = -1;
    Mat4 camera_world;
    SceneBuilder(const tinygltf::Model &m, snell_ctx *c, snell_scene_file *o) : model(m), ctx(c), out(o) {}
    ~SceneBuilder()
    {
        for (snell_mesh *m : owned) snell_mesh_destroy(m);
    }
    void node(int idx, const tinygltf::Node &n, const Mat4 &world) override;
    void add(const tinygltf::Primitive &p, int mesh_idx, int prim_idx, const Mat4 &world, int node);
    snell_mesh *mesh_of(const tinygltf::Primitive &p, int mesh_idx, int prim_idx);
    void note_ignored(const tinygltf::ExtensionMap &ext);
    void finish();
    void merge_opaque();
    void hand_over();
};

void SceneBuilder::note_ignored(const tinygltf::ExtensionMap &ext)
{
    for (const auto &e : ext)
        if (!scene_extension_known(e.first) && ignored.find(e.first) == std::string::npos)
            ignored += (ignored.empty() ? "" : ", ") + shown_uri(e.first);
}

snell_mesh *SceneBuilder::mesh_of(const tinygltf::Primitive &p, int mesh_idx, int prim_idx)
{
    auto key = std::make_pair(mesh_idx, prim_idx);
    auto it = meshes.find(key);
    if (it != meshes.end()) return it->second;
    Builder b(model, ctx);
    b.add_primitive(p, identity(), mesh_idx);
    snell_mesh *m = nullptr;
    if (!b.idx.empty()) {
        owned.reserve(owned.size() + 1);
        snell_status st = adopt(ctx, b, &m);
        if (st != SNELL_OK) fail(st, snell_last_error(ctx));
        owned.push_back(m);
    }
    meshes[key] = m;
    return m;
}

void SceneBuilder::add(const tinygltf::Primitive &p, int mesh_idx, int prim_idx, const Mat4 &world, int node)
{
    char buf[200];
    if (p.material < -1 || (p.material >= 0 && static_cast<size_t>(p.material) >= model.materials.size())) {
        std::snprintf(buf, sizeof buf, "mesh %d primitive %d: material %d does not exist", mesh_idx, prim_idx,
                      p.material);
        fail(SNELL_E_PARSE, buf);
    }
    snell_mesh *m = mesh_of(p, mesh_idx, prim_idx);
    if (!m) return; /* no triangles */
    for (int k = 0; k < 16; k++)
        if (!std::isfinite(world.m[k]) || std::fabs(world.m[k]) > 3.0e38) {
            std::snprintf(buf, sizeof buf, "node %d: its world transform is not finite", node);
            fail(SNELL_E_PARSE, buf);
        }
    {
        /* the object's model matrix: refused here, not by every frame that draws it */
        float mf[16];
        char why[96];
        for (int k = 0; k < 16; k++) mf[k] = static_cast<float>(world.m[k]);
        if (!snell__matrix_invertible(mf, why, sizeof why)) {
            std::snprintf(buf, sizeof buf, "node %d: its world transform %s", node, why);
            fail(SNELL_E_PARSE, buf);
        }
    }
    /* glTF's default material: opaque, base colour 1 */
    double base[4] = {1.0, 1.0, 1.0, 1.0};
    const tinygltf::Material *mat = p.material >= 0 ? &model.materials[static_cast<size_t>(p.material)] : nullptr;
    if (mat) {
        const std::vector<double> &bc = mat->pbrMetallicRoughness.baseColorFactor;
        if (bc.size() == 4)
            for (int k = 0; k < 4; k++) base[k] = std::isfinite(bc[static_cast<size_t>(k)]) ? bc[static_cast<size_t>(k)] : 1.0;
        note_ignored(mat->extensions);
    }
    double transmission = 0.0;
    auto ext = [&](const char *name) -> const tinygltf::Value * {
        if (!mat) return nullptr;
        auto e = mat->extensions.find(name);
        return e == mat->extensions.end() ? nullptr : &e->second;
    };
    if (const tinygltf::Value *t = ext("KHR_materials_transmission")) transmission = number_or(*t, "transmissionFactor", 0.0);
    if (transmission > 0.0) {
        /* Glass is not merged (each object is a refraction of its own): past
         * the limit the rest are still read and counted for the message. */
        snell_glass scratch;
        float scratch_model[16];
        bool kept = out->glass_count < SNELL_MAX_GLASS;
        snell_glass *g = kept ? &out->glass[out->glass_count] : &scratch;
        float *model_m = kept ? out->glass_model[out->glass_count] : scratch_model;
        std::memset(&scratch, 0, sizeof scratch);
        if (kept) node_name(model, node, out->glass_name[out->glass_count++]);
        glass_total++;
        g->mesh = m;
        g->model = model_m;
        for (int k = 0; k < 16; k++) model_m[k] = static_cast<float>(world.m[k]);
        double ior = 1.5;
        if (const tinygltf::Value *e = ext("KHR_materials_ior")) ior = number_or(*e, "ior", 1.5);
        if (!(ior >= 0.05 && ior <= 100.0)) {
            std::snprintf(buf, sizeof buf, "material %d: ior %g outside 0.05..100", p.material, ior);
            fail(SNELL_E_PARSE, buf);
        }
        g->material.ior = static_cast<float>(ior);
        for (int k = 0; k < 3; k++) g->material.tint[k] = static_cast<float>(std::min(std::max(base[k], 0.0), 1.0));
        if (g->material.tint[0] == 0.0f && g->material.tint[1] == 0.0f && g->material.tint[2] == 0.0f)
            g->material.tint[0] = g->material.tint[1] = g->material.tint[2] = 1e-6f; /* black, not "default white" */
        const tinygltf::Value *vol = ext("KHR_materials_volume");
        double thick = vol ? number_or(*vol, "thicknessFactor", 0.0) : 0.0;
        if (thick > 0.0) {
            double dist = number_or(*vol, "attenuationDistance", 0.0);
            if (dist < 0.0) fail(SNELL_E_PARSE, "KHR_materials_volume: attenuationDistance is negative");
            g->material.attenuation_distance = std::isinf(dist) ? 0.0f : static_cast<float>(dist);
            if (vol->Has("attenuationColor")) {
                const tinygltf::Value &c = vol->Get("attenuationColor");
                if (!c.IsArray() || c.ArrayLen() != 3) fail(SNELL_E_PARSE, "KHR_materials_volume: attenuationColor is not 3 numbers");
                for (int k = 0; k < 3; k++) {
                    const tinygltf::Value &ck = c.Get(k);
                    if (!ck.IsNumber() || !std::isfinite(ck.GetNumberAsDouble()))
                        fail(SNELL_E_PARSE, "KHR_materials_volume: attenuationColor is not 3 numbers");
                    g->material.attenuation_color[k] = static_cast<float>(std::min(std::max(ck.GetNumberAsDouble(), 0.0), 1.0));
                }
            }
            /* 20 / V_d (the spec: 0 none, any value >= 0 valid); on a volume
             * only, as the spec builds it on KHR_materials_volume */
            if (const tinygltf::Value *e = ext("KHR_materials_dispersion")) {
                double disp = number_or(*e, "dispersion", 0.0);
                if (!(disp >= 0.0 && disp <= 20.0)) {
                    std::snprintf(buf, sizeof buf, "material %d: KHR_materials_dispersion %g outside 0..20", p.material,
                                  disp);
                    fail(SNELL_E_PARSE, buf);
                }
                g->material.dispersion = static_cast<float>(disp);
            }
        } else {
            g->material.thickness = kThinWall;
        }
    } else {
        OpaqueInstance o;
        o.mesh = m;
        o.prim = &p;
        o.mesh_idx = mesh_idx;
        o.node = node;
        o.material = p.material;
        o.world = world;
        for (int k = 0; k < 3; k++) o.color[k] = static_cast<float>(std::min(std::max(base[k], 0.0), 1.0));
        if (o.color[0] == 0.0f && o.color[1] == 0.0f && o.color[2] == 0.0f) o.color[0] = 1e-6f; /* black */
        if (opaque.size() % 4096 == 0) { /* the list itself, as node instances can be many (kMaxInstances) */
            snell_status st = snell__budget_check(ctx, (opaque.size() + 4096) * sizeof(OpaqueInstance),
                                                  "the scene's opaque instances");
            if (st != SNELL_OK) fail(st, snell_last_error(ctx));
        }
        opaque.push_back(o);
    }
}

/* More opaque instances than SNELL_MAX_OPAQUE: one object per colour (all the
 * renderer draws of an opaque object), its instances' geometry in world space
 * (the node transforms baked in, model matrix identity); a colour with one
 * instance keeps its mesh and matrix. More colours than the limit is
 * SNELL_E_LIMIT. */
void SceneBuilder::merge_opaque()
{
    char buf[200];
    std::vector<std::vector<size_t>> groups;
    for (size_t i = 0; i < opaque.size(); i++) {
        size_t g = 0;
        while (g < groups.size() && std::memcmp(opaque[groups[g][0]].color, opaque[i].color, sizeof opaque[i].color) != 0) g++;
        if (g == groups.size()) {
            if (groups.size() == SNELL_MAX_OPAQUE) {
                std::snprintf(buf, sizeof buf,
                              "%zu opaque objects in more than %d colours: more than the limit of %d "
                              "(SNELL_MAX_OPAQUE) even merged per colour",
                              opaque.size(), SNELL_MAX_OPAQUE, SNELL_MAX_OPAQUE);
                fail(SNELL_E_LIMIT, buf);
            }
            groups.emplace_back();
        }
        groups[g].push_back(i);
    }
    for (const std::vector<size_t> &grp : groups) {
        const OpaqueInstance &first = opaque[grp[0]];
        int k = out->opaque_count;
        snell_opaque *o = &out->opaque[k];
        float *model_m = out->opaque_model[k];
        if (grp.size() == 1) {
            o->mesh = first.mesh;
            for (int j = 0; j < 16; j++) model_m[j] = static_cast<float>(first.world.m[j]);
            node_name(model, first.node, out->opaque_name[k]);
        } else {
            Builder b(model, ctx);
            for (size_t i : grp) b.add_primitive(*opaque[i].prim, opaque[i].world, opaque[i].mesh_idx);
            if (b.idx.empty()) continue; /* every instance scaled to nothing */
            snell_mesh *merged = nullptr;
            owned.reserve(owned.size() + 1);
            snell_status st = adopt(ctx, b, &merged);
            if (st != SNELL_OK) fail(st, snell_last_error(ctx));
            owned.push_back(merged);
            o->mesh = merged;
            for (int j = 0; j < 16; j++) model_m[j] = j % 5 == 0 ? 1.0f : 0.0f;
            std::string mn = first.material >= 0 ? model.materials[static_cast<size_t>(first.material)].name : "";
            mn = mn.empty() ? "material " + std::to_string(first.material) : "'" + mn + "'";
            copy_name(std::to_string(grp.size()) + " nodes of " + mn, out->opaque_name[k]);
        }
        o->model = model_m;
        std::memcpy(o->color, first.color, sizeof o->color);
        out->opaque_count++;
    }
    snell__log(ctx, SNELL_LOG_INFO, "glTF scene: %zu opaque objects (more than SNELL_MAX_OPAQUE %d) merged "
               "into %d, one per colour", opaque.size(), SNELL_MAX_OPAQUE, out->opaque_count);
}

/* The meshes the lists use go to the scene file, the rest (primitives only
 * drawn merged) are destroyed with the builder. */
void SceneBuilder::hand_over()
{
    for (snell_mesh *&m : owned) {
        bool used = false;
        for (int i = 0; i < out->glass_count && !used; i++) used = out->glass[i].mesh == m;
        for (int i = 0; i < out->opaque_count && !used; i++) used = out->opaque[i].mesh == m;
        if (used && out->mesh_count < SNELL_MAX_GLASS + SNELL_MAX_OPAQUE) { /* at most one per object */
            out->meshes[out->mesh_count++] = m;
            m = nullptr;
        }
    }
}

void SceneBuilder::finish()
{
    char buf[200];
    if (glass_total > SNELL_MAX_GLASS) {
        std::snprintf(buf, sizeof buf, "%d glass objects: more than the limit of %d (SNELL_MAX_GLASS; glass "
                      "objects are not merged)", glass_total, SNELL_MAX_GLASS);
        fail(SNELL_E_LIMIT, buf);
    }
    if (opaque.size() <= SNELL_MAX_OPAQUE) {
        for (const OpaqueInstance &i : opaque) {
            int k = out->opaque_count++;
            out->opaque[k].mesh = i.mesh;
            out->opaque[k].model = out->opaque_model[k];
            for (int j = 0; j < 16; j++) out->opaque_model[k][j] = static_cast<float>(i.world.m[j]);
            std::memcpy(out->opaque[k].color, i.color, sizeof i.color);
            node_name(model, i.node, out->opaque_name[k]);
        }
    } else {
        merge_opaque();
    }
    hand_over();
    /* the bounding sphere of every object's world vertices: centred on their box */
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, r2 = 0.0;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < out->glass_count + out->opaque_count; i++) {
            const snell_mesh *m = i < out->glass_count ? out->glass[i].mesh : out->opaque[i - out->glass_count].mesh;
            const float *M = i < out->glass_count ? out->glass[i].model : out->opaque[i - out->glass_count].model;
            for (uint32_t v = 0; v < m->vertex_count; v++) {
                const float *p = &m->positions[3 * v];
                double w[3], d2 = 0.0;
                for (int r = 0; r < 3; r++) {
                    w[r] = static_cast<double>(M[r]) * p[0] + static_cast<double>(M[4 + r]) * p[1] +
                           static_cast<double>(M[8 + r]) * p[2] + M[12 + r];
                    if (pass == 0) {
                        lo[r] = std::min(lo[r], w[r]);
                        hi[r] = std::max(hi[r], w[r]);
                    } else {
                        double d = w[r] - 0.5 * (lo[r] + hi[r]);
                        d2 += d * d;
                    }
                }
                r2 = std::max(r2, d2);
            }
        }
    for (int r = 0; r < 3; r++) out->centre[r] = static_cast<float>(0.5 * (lo[r] + hi[r]));
    out->radius = static_cast<float>(std::sqrt(r2));
}

void SceneBuilder::node(int idx, const tinygltf::Node &n, const Mat4 &world)
{
    if (n.camera >= 0 && camera_node < 0) {
        if (static_cast<size_t>(n.camera) >= model.cameras.size()) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "node %d references missing camera %d", idx, n.camera);
            fail(SNELL_E_PARSE, buf);
        }
        camera_node = idx;
        camera_world = world;
    }
    if (n.mesh < 0) return;
    const std::vector<tinygltf::Primitive> &prims = model.meshes[static_cast<size_t>(n.mesh)].primitives;
    for (size_t i = 0; i < prims.size(); i++) add(prims[i], n.mesh, static_cast<int>(i), world, idx);
}

/* The glTF camera (a pose and a perspective) as snell's orbit camera: the
 * eye and view direction are kept, the target put on the view axis at the
 * depth of the scene's centre, the roll dropped (snell's up is +Y). */
void convert_camera(const tinygltf::Camera &c, const Mat4 &w, const snell_scene_file *s, snell_camera *cam)
{
    double eye[3] = {w.m[12], w.m[13], w.m[14]}, fwd[3] = {-w.m[8], -w.m[9], -w.m[10]}, centre[3] = {0, 0, 0};
    double len = std::sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]), dist = 0.0;
    int n = 0;
    if (!(len > 0.0)) fail(SNELL_E_PARSE, "the camera's node transform is degenerate");
    for (int k = 0; k < 3; k++) fwd[k] /= len;
    /* the scene's centre: the mean of the objects' origins */
    for (int i = 0; i < s->glass_count; i++, n++)
        for (int k = 0; k < 3; k++) centre[k] += s->glass_model[i][12 + k];
    for (int i = 0; i < s->opaque_count; i++, n++)
        for (int k = 0; k < 3; k++) centre[k] += s->opaque_model[i][12 + k];
    for (int k = 0; k < 3 && n; k++) dist += (centre[k] / n - eye[k]) * fwd[k];
    if (!(dist > 1e-3)) dist = 1.0;
    std::memset(cam, 0, sizeof *cam);
    for (int k = 0; k < 3; k++) cam->target[k] = static_cast<float>(eye[k] + dist * fwd[k]);
    cam->distance = static_cast<float>(dist);
    cam->elevation = static_cast<float>(std::asin(std::min(std::max(-fwd[1], -1.0), 1.0)));
    cam->azimuth = static_cast<float>(std::atan2(-fwd[0], -fwd[2]));
    if (c.type == "perspective") {
        if (!(c.perspective.yfov > 0.0 && c.perspective.yfov < 3.14159))
            fail(SNELL_E_PARSE, "camera: perspective yfov outside (0, pi)");
        cam->fov_y = static_cast<float>(c.perspective.yfov);
        if (c.perspective.znear > 0.0) cam->z_near = static_cast<float>(c.perspective.znear);
        if (c.perspective.zfar > c.perspective.znear) cam->z_far = static_cast<float>(c.perspective.zfar);
    }
}

snell_status load_scene(snell_ctx *ctx, const unsigned char *data, size_t size, const std::string &base_dir,
                        bool allow_files, unsigned flags, snell_scene_file **out)
{
    const snell_alloc *al = snell__ctx_alloc(ctx);
    snell_scene_file *s = static_cast<snell_scene_file *>(snell__calloc(al, 1, sizeof(snell_scene_file)));
    if (!s) return snell__fail(ctx, SNELL_E_NOMEM, "glTF scene: out of memory");
    s->alloc = *al;
    try {
        tinygltf::Model model;
        parse(ctx, data, size, base_dir, allow_files, flags, model);
        std::string bad;
        for (const std::string &e : model.extensionsRequired)
            if (e.compare(0, 14, "KHR_materials_") == 0 && !scene_extension_known(e))
                bad += (bad.empty() ? "" : ", ") + shown_uri(e);
        if (!bad.empty()) fail(SNELL_E_UNSUPPORTED, "the scene requires material extensions that are not supported: " + bad);
        SceneBuilder b(model, ctx, s);
        walk_nodes(model, b);
        if (b.glass_total == 0 && b.opaque.empty()) fail(SNELL_E_PARSE, "no triangle primitives in the scene");
        b.finish();
        if (!b.ignored.empty())
            snell__log(ctx, SNELL_LOG_INFO, "glTF scene: ignored extensions %s", b.ignored.c_str());
        if (b.camera_node >= 0) {
            convert_camera(model.cameras[static_cast<size_t>(model.nodes[static_cast<size_t>(b.camera_node)].camera)],
                           b.camera_world, s, &s->camera);
            s->has_camera = 1;
        } else {
            snell__log(ctx, SNELL_LOG_INFO, "glTF scene: no camera in the file; its objects' bounding sphere: centre "
                       "(%g, %g, %g), radius %g (snell_scene_file_frame frames it)", s->centre[0], s->centre[1],
                       s->centre[2], s->radius);
        }
        *out = s;
        return SNELL_OK;
    } catch (const LoadError &e) {
        snell_scene_file_destroy(s);
        return snell__fail(ctx, e.status, "glTF scene: %s", e.msg.c_str());
    } catch (const std::bad_alloc &) {
        snell_scene_file_destroy(s);
        return snell__fail(ctx, SNELL_E_NOMEM, "glTF scene: out of memory");
    } catch (const std::exception &e) {
        snell_scene_file_destroy(s);
        return snell__fail(ctx, SNELL_E_PARSE, "glTF scene: %s", e.what());
    } catch (...) {
        snell_scene_file_destroy(s);
        return snell__fail(ctx, SNELL_E_PARSE, "glTF scene: unexpected exception");
    }
}

/* Reads the model file itself: a regular file (not a directory or device),
 * at most 1 GiB and within the memory budget. */
snell_status read_model_file(snell_ctx *ctx, const char *path, std::vector<unsigned char> *bytes)
{
    int opened;
    const char *why;
    int fd = snell__open_regular(path, &opened, &why);
    struct stat sb;
    if (fd < 0 && !opened) return snell__fail(ctx, SNELL_E_IO, "cannot open '%s': %s", path, why);
    if (fd < 0) return snell__fail(ctx, SNELL_E_IO, "glTF: '%s' is %s", path, why);
    if (fstat(fd, &sb) != 0) {
        close(fd);
        return snell__fail(ctx, SNELL_E_IO, "glTF: cannot stat '%s'", path);
    }
    if (static_cast<unsigned long long>(sb.st_size) > kMaxInputBytes) {
        close(fd);
        return snell__fail(ctx, SNELL_E_LIMIT, "'%s' is larger than 1 GiB", path);
    }
    size_t size = static_cast<size_t>(sb.st_size);
    char what[320];
    std::snprintf(what, sizeof what, "glTF: reading '%.256s'", path); /* reported as is */
    snell_status st = snell__budget_check(ctx, size, what);
    if (st != SNELL_OK) {
        close(fd);
        return st;
    }
    bytes->resize(size);
    size_t got = 0;
    while (got < size) {
        ssize_t n = read(fd, bytes->data() + got, size - got);
        if (n <= 0) break;
        got += static_cast<size_t>(n);
    }
    close(fd);
    if (got != size) return snell__fail(ctx, SNELL_E_IO, "glTF: short read on '%s'", path);
    return SNELL_OK;
}

/* The model file (non-empty) and its folder, which external buffers are
 * resolved against. */
snell_status read_model_file_and_dir(snell_ctx *ctx, const char *path, std::vector<unsigned char> *bytes,
                                     std::string *dir)
{
    snell_status st = read_model_file(ctx, path, bytes);
    if (st != SNELL_OK) return st;
    if (bytes->empty()) return snell__fail(ctx, SNELL_E_PARSE, "glTF: '%s' is empty", path);
    std::string p(path);
    size_t slash = p.find_last_of('/');
    if (slash != std::string::npos) *dir = p.substr(0, slash + 1);
    return SNELL_OK;
}

/* A path loader's checks and its file read, then loader (load or load_scene)
 * on the bytes, with the file's folder for external buffers; fn names the
 * API call in the messages. */
template <typename T>
snell_status load_path(snell_ctx *ctx, const char *fn, const char *path, unsigned flags, T **out,
                       snell_status (*loader)(snell_ctx *, const unsigned char *, size_t, const std::string &, bool,
                                              unsigned, T **))
{
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: out is NULL", fn);
    *out = NULL;
    if (!path) return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: path is NULL", fn);
    if (flags & ~static_cast<unsigned>(SNELL_LOAD_ALLOW_OUTSIDE_FOLDER))
        return snell__fail(ctx, SNELL_E_INVALID_ARG, "%s: unknown flags 0x%x", fn, flags);
    try {
        std::vector<unsigned char> bytes;
        std::string dir;
        snell_status st = read_model_file_and_dir(ctx, path, &bytes, &dir);
        return st != SNELL_OK ? st : loader(ctx, bytes.data(), bytes.size(), dir, true, flags, out);
    } catch (...) {
        return snell__fail(ctx, SNELL_E_NOMEM, "glTF: out of memory reading '%s'", path);
    }
}

} // namespace

extern "C" snell_status snell_mesh_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out)
{
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf_mem: out is NULL");
    *out = NULL;
    if (!data || !size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf_mem: no data");
    return load(ctx, static_cast<const unsigned char *>(data), size, "", false, 0, out);
}

extern "C" snell_status snell_mesh_load_gltf_ex(snell_ctx *ctx, const char *path, unsigned flags, snell_mesh **out)
{
    return load_path(ctx, "snell_mesh_load_gltf", path, flags, out, load);
}

extern "C" snell_status snell_mesh_load_gltf(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    return snell_mesh_load_gltf_ex(ctx, path, 0, out);
}

extern "C" void snell_scene_file_destroy(snell_scene_file *s)
{
    if (!s) return;
    snell_alloc al = s->alloc;
    for (int i = 0; i < s->mesh_count; i++) snell_mesh_destroy(s->meshes[i]);
    snell__free(&al, s);
}

extern "C" snell_status snell_scene_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size,
                                                   snell_scene_file **out)
{
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_scene_load_gltf_mem: out is NULL");
    *out = NULL;
    if (!data || !size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_scene_load_gltf_mem: no data");
    return load_scene(ctx, static_cast<const unsigned char *>(data), size, "", false, 0, out);
}

extern "C" snell_status snell_scene_load_gltf(snell_ctx *ctx, const char *path, unsigned flags, snell_scene_file **out)
{
    return load_path(ctx, "snell_scene_load_gltf", path, flags, out, load_scene);
}

extern "C" const snell_glass *snell_scene_file_glass(const snell_scene_file *s, int *count)
{
    if (count) *count = s ? s->glass_count : 0;
    return s && s->glass_count ? s->glass : NULL;
}

extern "C" const snell_opaque *snell_scene_file_opaque(const snell_scene_file *s, int *count)
{
    if (count) *count = s ? s->opaque_count : 0;
    return s && s->opaque_count ? s->opaque : NULL;
}

extern "C" int snell_scene_file_camera(const snell_scene_file *s, snell_camera *camera)
{
    if (!s || !s->has_camera) return 0;
    if (camera) *camera = s->camera;
    return 1;
}

extern "C" snell_status snell_scene_file_frame(const snell_scene_file *s, float aspect, snell_camera *camera)
{
    if (!s || !camera) return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_scene_file_frame: %s is NULL",
                                          !s ? "scene" : "camera");
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_scene_file_frame: aspect %g is not a finite width / height > 0",
                           static_cast<double>(aspect));
    double fov = camera->fov_y > 0.0f ? camera->fov_y : 45.0 * 3.14159265358979323846 / 180.0;
    if (!(camera->fov_y >= 0.0f) || !(fov < 3.14159265358979323846))
        return snell__fail(NULL, SNELL_E_INVALID_ARG, "snell_scene_file_frame: camera.fov_y %g outside [0, pi)",
                           static_cast<double>(camera->fov_y));
    /* the sphere fits the narrower of the two half-angles, with 5% to spare */
    double half_v = 0.5 * fov, half_h = std::atan(aspect * std::tan(half_v));
    double r = s->radius > 0.0f ? s->radius : 1e-3, dist = 1.05 * r / std::sin(std::min(half_v, half_h));
    if (!std::isfinite(dist) || dist > 1e30)
        return snell__fail(NULL, SNELL_E_LIMIT, "snell_scene_file_frame: the scene's bounding sphere (radius %g) is "
                           "too large to frame", static_cast<double>(s->radius));
    for (int k = 0; k < 3; k++) camera->target[k] = s->centre[k];
    camera->distance = static_cast<float>(dist);
    camera->z_near = camera->z_far = 0.0f; /* derived from the distance: 0.01 d .. 100 d holds the sphere */
    return SNELL_OK;
}

static const char *scene_name(const snell_scene_file *s, int i, int count, const char (*names)[SNELL__SCENE_NAME])
{
    return s && i >= 0 && i < count ? names[i] : NULL;
}

extern "C" const char *snell_scene_file_glass_name(const snell_scene_file *s, int i)
{
    return scene_name(s, i, s ? s->glass_count : 0, s ? s->glass_name : NULL);
}

extern "C" const char *snell_scene_file_opaque_name(const snell_scene_file *s, int i)
{
    return scene_name(s, i, s ? s->opaque_count : 0, s ? s->opaque_name : NULL);
}
