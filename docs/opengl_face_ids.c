/* A face-id image of an OBJ rendered with OpenGL, for `sightline compare INPUT --image`.
 *
 *   cc -O2 -o opengl_face_ids docs/opengl_face_ids.c -lEGL -lGL
 *   ./opengl_face_ids MESH.obj VIEW.cam OUT.png
 *   sightline compare MESH.obj --cam VIEW.cam --image OUT.png --diff where.png
 *
 * Headless (EGL, no window: Mesa's surfaceless platform, or any EGL device), OpenGL 3.3 core.
 * What makes the output sightline's `--fill id` contract (docs/compare_image.md):
 * - face k of the file (the k-th `f` line, counting from 0) gets the id k, carried to every
 *   fragment as a `flat` integer attribute (the same on each corner of the face's triangles);
 * - the fragment shader writes id + 1 as an unsigned integer into a GL_R32UI colour buffer
 *   cleared to 0: no conversion to normalized colour, so no rounding, blending, dithering or
 *   sRGB encoding can touch it (an RGB8 target works too if GL_FRAMEBUFFER_SRGB, blending,
 *   dithering and multisampling are off, but an integer target cannot get them wrong);
 * - a single-sample framebuffer: one sample at each pixel centre;
 * - the projection is sightline's camera (gluLookAt then gluPerspective, or glOrtho with the
 *   view height, aspect = width / height), computed in double and used in float;
 * - the image is read back with glReadPixels (row 0 at the bottom, OpenGL's) and written top
 *   row first (sightline's), each id + 1 packed as r = v >> 16, g = v >> 8, b = v (8 bits each).
 * Faces are drawn as triangle fans: right for convex faces; triangulate non-convex ones
 * properly in your own renderer. Depth test GL_LESS on a 32-bit float depth buffer.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void die(const char *what) {
    fprintf(stderr, "opengl_face_ids: error: %s\n", what);
    exit(1);
}

/* ------------------------------------------------------------------ the .cam file */
typedef struct {
    double eye[3], target[3], up[3], fovy, ortho_height, near, far;
    int width, height;
} Cam;

static Cam read_cam(const char *path) {
    Cam c = {.fovy = 40, .ortho_height = 1, .near = 0.1, .far = 100, .width = 1024, .height = 1024};
    FILE *f = fopen(path, "r");
    if (!f) die("cannot open the camera file");
    char key[64];
    while (fscanf(f, " %63s", key) == 1) {
        if (key[0] == '#') { int ch; while ((ch = fgetc(f)) != '\n' && ch != EOF) {} continue; }
        if (!strcmp(key, "eye")) fscanf(f, "%lf %lf %lf", &c.eye[0], &c.eye[1], &c.eye[2]);
        else if (!strcmp(key, "target")) fscanf(f, "%lf %lf %lf", &c.target[0], &c.target[1], &c.target[2]);
        else if (!strcmp(key, "up")) fscanf(f, "%lf %lf %lf", &c.up[0], &c.up[1], &c.up[2]);
        else if (!strcmp(key, "fovy")) fscanf(f, "%lf", &c.fovy);
        else if (!strcmp(key, "ortho_height")) fscanf(f, "%lf", &c.ortho_height);
        else if (!strcmp(key, "near")) fscanf(f, "%lf", &c.near);
        else if (!strcmp(key, "far")) fscanf(f, "%lf", &c.far);
        else if (!strcmp(key, "size")) fscanf(f, "%d %d", &c.width, &c.height);
    }
    fclose(f);
    return c;
}

/* Column-major 4x4: m[col * 4 + row], as OpenGL takes it. */
static void mul(const double *a, const double *b, double *out) {
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

static void normalize(double *v) {
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= n;
}

static void cross(const double *a, const double *b, double *o) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* gluPerspective (or glOrtho) times gluLookAt: sightline's camera (src/camera.rs). */
static void view_projection(const Cam *c, float *out) {
    double f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]};
    normalize(f);
    double s[3], u[3];
    cross(f, c->up, s);
    normalize(s);
    cross(s, f, u);
    double view[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                       -(s[0] * c->eye[0] + s[1] * c->eye[1] + s[2] * c->eye[2]),
                       -(u[0] * c->eye[0] + u[1] * c->eye[1] + u[2] * c->eye[2]),
                       (f[0] * c->eye[0] + f[1] * c->eye[1] + f[2] * c->eye[2]), 1};
    double aspect = (double)c->width / c->height, n = c->near, fa = c->far, proj[16] = {0};
    if (c->fovy > 0) {
        double t = 1.0 / tan(c->fovy * M_PI / 360.0);
        proj[0] = t / aspect;
        proj[5] = t;
        proj[10] = (fa + n) / (n - fa);
        proj[11] = -1;
        proj[14] = 2 * fa * n / (n - fa);
    } else {
        double hh = c->ortho_height / 2, hw = hh * aspect;
        proj[0] = 1 / hw;
        proj[5] = 1 / hh;
        proj[10] = -2 / (fa - n);
        proj[14] = -(fa + n) / (fa - n);
        proj[15] = 1;
    }
    double m[16];
    mul(proj, view, m);
    for (int i = 0; i < 16; i++) out[i] = (float)m[i];
}

/* ------------------------------------------------------------------ the OBJ */
typedef struct { float *xyz; uint32_t *id; size_t n, cap; } Tris; /* 3 corners per triangle */

static void push(Tris *t, const float *p, uint32_t id) {
    if (t->n == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 1024;
        t->xyz = realloc(t->xyz, t->cap * 3 * sizeof(float));
        t->id = realloc(t->id, t->cap * sizeof(uint32_t));
        if (!t->xyz || !t->id) die("out of memory");
    }
    memcpy(t->xyz + 3 * t->n, p, 3 * sizeof(float));
    t->id[t->n++] = id;
}

static Tris read_obj(const char *path, uint32_t *faces) {
    FILE *f = fopen(path, "r");
    if (!f) die("cannot open the OBJ");
    float *v = NULL;
    size_t nv = 0, capv = 0;
    Tris t = {0};
    *faces = 0;
    char line[1 << 16];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == capv) { capv = capv ? 2 * capv : 1024; v = realloc(v, capv * 3 * sizeof(float)); }
            sscanf(line + 2, "%f %f %f", &v[3 * nv], &v[3 * nv + 1], &v[3 * nv + 2]);
            nv++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            long idx[1024];
            int k = 0;
            for (char *tok = strtok(line + 2, " \t\r\n"); tok && k < 1024; tok = strtok(NULL, " \t\r\n")) {
                long i = strtol(tok, NULL, 10);
                idx[k++] = i > 0 ? i - 1 : (long)nv + i;
            }
            for (int j = 1; j + 1 < k; j++) { /* a fan from the first corner */
                push(&t, &v[3 * idx[0]], *faces);
                push(&t, &v[3 * idx[j]], *faces);
                push(&t, &v[3 * idx[j + 1]], *faces);
            }
            (*faces)++;
        }
    }
    fclose(f);
    free(v);
    return t;
}

/* ------------------------------------------------------------------ PNG (stored deflate) */
static uint32_t crc_table[256];

static uint32_t crc(uint32_t c, const uint8_t *p, size_t n) {
    if (!crc_table[1])
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t x = i;
            for (int k = 0; k < 8; k++) x = x & 1 ? 0xEDB88320u ^ (x >> 1) : x >> 1;
            crc_table[i] = x;
        }
    c = ~c;
    while (n--) c = crc_table[(c ^ *p++) & 255] ^ (c >> 8);
    return ~c;
}

static void be32(uint8_t *p, uint32_t v) { p[0] = v >> 24; p[1] = v >> 16; p[2] = v >> 8; p[3] = v; }

static void chunk(FILE *f, const char *type, const uint8_t *data, uint32_t n) {
    uint8_t b[4];
    be32(b, n);
    fwrite(b, 1, 4, f);
    fwrite(type, 1, 4, f);
    fwrite(data, 1, n, f);
    be32(b, crc(crc(0, (const uint8_t *)type, 4), data, n));
    fwrite(b, 1, 4, f);
}

/* rows: height rows of 1 + 3 * width bytes (filter byte 0, then RGB). */
static void write_png(const char *path, int w, int h, const uint8_t *rows) {
    size_t n = (size_t)h * (1 + 3 * (size_t)w), blocks = n / 65535 + 1;
    uint8_t *z = malloc(2 + n + 5 * blocks + 4);
    size_t o = 0;
    uint32_t a = 1, b = 0;
    z[o++] = 0x78;
    z[o++] = 0x01;
    for (size_t at = 0; at < n || at == 0; at += 65535) {
        size_t len = n - at < 65535 ? n - at : 65535;
        z[o++] = at + len == n;
        z[o++] = len & 255; z[o++] = len >> 8; z[o++] = ~len & 255; z[o++] = (~len >> 8) & 255;
        memcpy(z + o, rows + at, len);
        o += len;
        if (at + len == n) break;
    }
    for (size_t i = 0; i < n; i++) { a = (a + rows[i]) % 65521; b = (b + a) % 65521; }
    be32(z + o, b << 16 | a);
    o += 4;
    FILE *f = fopen(path, "wb");
    if (!f) die("cannot write the PNG");
    fwrite("\x89PNG\r\n\x1a\n", 1, 8, f);
    uint8_t ihdr[13];
    be32(ihdr, w);
    be32(ihdr + 4, h);
    ihdr[8] = 8; ihdr[9] = 2; ihdr[10] = ihdr[11] = ihdr[12] = 0; /* 8-bit RGB */
    chunk(f, "IHDR", ihdr, 13);
    chunk(f, "IDAT", z, (uint32_t)o);
    chunk(f, "IEND", NULL, 0);
    fclose(f);
    free(z);
}

/* ------------------------------------------------------------------ GL */
static const char *VS =
    "#version 330 core\n"
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in uint face_id;\n"
    "uniform mat4 view_projection;\n"
    "flat out uint id;\n"
    "void main() { gl_Position = view_projection * vec4(position, 1.0); id = face_id; }\n";
static const char *FS =
    "#version 330 core\n"
    "flat in uint id;\n"
    "layout(location = 0) out uint label;\n"
    "void main() { label = id + 1u; }\n";

static GLuint shader(GLenum kind, const char *src) {
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) die("shader does not compile");
    return s;
}

int main(int argc, char **argv) {
    if (argc != 4) die("usage: opengl_face_ids MESH.obj VIEW.cam OUT.png");
    Cam cam = read_cam(argv[2]);
    uint32_t faces;
    Tris tris = read_obj(argv[1], &faces);
    fprintf(stderr, "opengl_face_ids: %u faces, %zu triangles, %dx%d\n", faces, tris.n / 3, cam.width, cam.height);

    /* A context with no window. */
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                                 : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (!eglInitialize(dpy, NULL, NULL)) die("no EGL display");
    eglBindAPI(EGL_OPENGL_API);
    /* No window, so no config is needed (EGL_KHR_no_config_context); else any with OpenGL. */
    EGLint cfg_attrs[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE}, nc;
    EGLConfig cfg = EGL_NO_CONFIG_KHR;
    if (!strstr(eglQueryString(dpy, EGL_EXTENSIONS), "EGL_KHR_no_config_context") &&
        (!eglChooseConfig(dpy, cfg_attrs, &cfg, 1, &nc) || nc < 1))
        die("no EGL config");
    EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attrs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        die("no OpenGL 3.3 context");
    fprintf(stderr, "opengl_face_ids: %s, %s\n", glGetString(GL_RENDERER), glGetString(GL_VERSION));

    /* Framebuffer: one unsigned integer per pixel, one sample, and depth. */
    GLuint fbo, color, depth;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, cam.width, cam.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, cam.width, cam.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) die("framebuffer incomplete");

    GLuint prog = glCreateProgram();
    glAttachShader(prog, shader(GL_VERTEX_SHADER, VS));
    glAttachShader(prog, shader(GL_FRAGMENT_SHADER, FS));
    glLinkProgram(prog);
    glUseProgram(prog);
    float vp[16];
    view_projection(&cam, vp);
    glUniformMatrix4fv(glGetUniformLocation(prog, "view_projection"), 1, GL_FALSE, vp);

    GLuint vao, buf[2];
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
    glBufferData(GL_ARRAY_BUFFER, tris.n * 3 * sizeof(float), tris.xyz, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, 0);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, buf[1]);
    glBufferData(GL_ARRAY_BUFFER, tris.n * sizeof(uint32_t), tris.id, GL_STATIC_DRAW);
    glVertexAttribIPointer(1, 1, GL_UNSIGNED_INT, 0, 0); /* I: stays an integer */
    glEnableVertexAttribArray(1);

    glViewport(0, 0, cam.width, cam.height);
    glDisable(GL_BLEND);
    glDisable(GL_DITHER);
    glDisable(GL_MULTISAMPLE);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_CULL_FACE); /* sightline culls only closed meshes' back faces, which are hidden */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const GLuint background[4] = {0, 0, 0, 0};
    const GLfloat far_depth = 1.0f;
    glClearBufferuiv(GL_COLOR, 0, background);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)tris.n);

    size_t w = cam.width, h = cam.height;
    uint32_t *ids = malloc(w * h * sizeof(uint32_t));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, cam.width, cam.height, GL_RED_INTEGER, GL_UNSIGNED_INT, ids);
    if (glGetError() != GL_NO_ERROR) die("OpenGL error");
    uint8_t *rows = malloc(h * (1 + 3 * w));
    for (size_t j = 0; j < h; j++) {
        uint8_t *row = rows + j * (1 + 3 * w);
        const uint32_t *src = ids + (h - 1 - j) * w; /* OpenGL's row 0 is the bottom one */
        row[0] = 0;
        for (size_t i = 0; i < w; i++) {
            uint32_t v = src[i];
            row[1 + 3 * i] = v >> 16 & 255;
            row[2 + 3 * i] = v >> 8 & 255;
            row[3 + 3 * i] = v & 255;
        }
    }
    write_png(argv[3], cam.width, cam.height, rows);
    fprintf(stderr, "opengl_face_ids: wrote %s\n", argv[3]);
    return 0;
}
