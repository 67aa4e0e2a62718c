/* Chipmunk as pymunk builds it (Munk2D): the struct layouts the helper reads and the functions it calls.

   The structs mirror pymunk's own cffi declarations; tm_layout reports their offsets and the loader compares them
   with pymunk's ffi (a mismatch: the helper is not used). Functions are called through pointers taken from
   pymunk's compiled module (tm_bind), so nothing is linked against it. */

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct cpVect { double x, y; } cpVect;

typedef struct cpContact {
    cpVect r1, r2;
    double nMass, tMass, bounce, jnAcc, jtAcc, jBias, bias;
    uintptr_t hash;
} cpContact;

typedef struct tm_arbiter_thread { void *next, *prev; } tm_arbiter_thread;

struct cpArbiter {
    double e, u;
    cpVect surface_vr;
    void *data;
    cpShape *a, *b;
    cpBody *body_a, *body_b;
    tm_arbiter_thread thread_a, thread_b;
    int count;
    cpContact *contacts;
    cpVect n;
    void *handlerAB, *handlerBA, *handlerA, *handlerB;
    unsigned char swapped;
    unsigned int stamp;
    int state;
    unsigned char processCollision;
};

typedef struct tm_point_pair { cpVect pointA, pointB; double distance; } tm_point_pair;
typedef struct cpContactPointSet { int count; cpVect normal; tm_point_pair points[2]; } cpContactPointSet;

typedef struct tm_handler {
    uintptr_t typeA, typeB;
    void *beginFunc, *preSolveFunc, *postSolveFunc, *separateFunc;
    void *userData;
} tm_handler;

typedef void (*tm_velocity_func)(cpBody *, cpVect, double, double);
typedef void (*tm_arbiter_iter)(cpBody *, cpArbiter *, void *);

/* Chipmunk's functions, bound by name (tm_bind) */
static struct {
    cpVect (*cpArbiterGetNormal)(cpArbiter *);
    int (*cpArbiterGetCount)(cpArbiter *);
    cpVect (*cpArbiterGetPointA)(cpArbiter *, int);
    cpVect (*cpArbiterGetPointB)(cpArbiter *, int);
    cpContactPointSet (*cpArbiterGetContactPointSet)(cpArbiter *);
    void (*cpArbiterSetFriction)(cpArbiter *, double);
    double (*cpArbiterGetFriction)(cpArbiter *);
    void (*cpArbiterGetBodies)(cpArbiter *, cpBody **, cpBody **);
    void (*cpArbiterGetShapes)(cpArbiter *, cpShape **, cpShape **);
    uintptr_t (*cpShapeGetCollisionType)(cpShape *);
    cpBody *(*cpShapeGetBody)(cpShape *);
    cpVect (*cpBodyGetPosition)(cpBody *);
    cpVect (*cpBodyGetVelocity)(cpBody *);
    double (*cpBodyGetAngularVelocity)(cpBody *);
    double (*cpBodyGetAngle)(cpBody *);
    void (*cpBodySetPosition)(cpBody *, cpVect);
    void (*cpBodySetVelocity)(cpBody *, cpVect);
    void (*cpBodySetAngle)(cpBody *, double);
    void (*cpBodySetAngularVelocity)(cpBody *, double);
    void (*cpBodySetVelocityUpdateFunc)(cpBody *, tm_velocity_func);
    void (*cpBodyUpdateVelocity)(cpBody *, cpVect, double, double);
    void (*cpBodyEachArbiter)(cpBody *, tm_arbiter_iter, void *);
    cpSpace *(*cpBodyGetSpace)(cpBody *);
    cpVect (*cpBodyLocalToWorld)(cpBody *, cpVect);
    double (*cpShapePointQuery)(cpShape *, cpVect, void *);
    void (*cpSpaceStep)(cpSpace *, double);
    void *(*cpSpaceGetUserData)(cpSpace *);
    void (*cpSpaceSetUserData)(cpSpace *, void *);
    void (*cpSpaceReindexShapesForBody)(cpSpace *, cpBody *);
    unsigned char (*cpArbiterIsRemoval)(cpArbiter *);
} CP;

static const char *const CP_NAMES[] = {
    "cpArbiterGetNormal", "cpArbiterGetCount", "cpArbiterGetPointA", "cpArbiterGetPointB",
    "cpArbiterGetContactPointSet", "cpArbiterSetFriction", "cpArbiterGetFriction", "cpArbiterGetBodies",
    "cpArbiterGetShapes", "cpShapeGetCollisionType", "cpShapeGetBody", "cpBodyGetPosition", "cpBodyGetVelocity",
    "cpBodyGetAngularVelocity", "cpBodyGetAngle", "cpBodySetPosition", "cpBodySetVelocity", "cpBodySetAngle",
    "cpBodySetAngularVelocity", "cpBodySetVelocityUpdateFunc", "cpBodyUpdateVelocity", "cpBodyEachArbiter",
    "cpBodyGetSpace", "cpBodyLocalToWorld", "cpShapePointQuery", "cpSpaceStep", "cpSpaceGetUserData",
    "cpSpaceSetUserData", "cpSpaceReindexShapesForBody", "cpArbiterIsRemoval",
};

/* Bind Chipmunk function `name` to `fn`; returns how many of the table's functions are still unbound, or -1 for an
   unknown name. */
int tm_bind(const char *name, void *fn) {
    void **slot = (void **)&CP;
    int n = (int)(sizeof(CP_NAMES) / sizeof(CP_NAMES[0])), missing = 0, found = 0;
    for (int i = 0; i < n; i++) {
        if (strcmp(CP_NAMES[i], name) == 0) {
            slot[i] = fn;
            found = 1;
        }
        missing += slot[i] == NULL;
    }
    return found ? missing : -1;
}

/* The mirrored layouts: sizes and field offsets, in the order the loader compares them; returns how many. */
int tm_layout(long *out, int n) {
    long v[] = {
        (long)sizeof(struct cpArbiter), (long)offsetof(struct cpArbiter, u), (long)offsetof(struct cpArbiter, surface_vr),
        (long)offsetof(struct cpArbiter, a), (long)offsetof(struct cpArbiter, b), (long)offsetof(struct cpArbiter, body_a),
        (long)offsetof(struct cpArbiter, body_b), (long)offsetof(struct cpArbiter, count),
        (long)offsetof(struct cpArbiter, contacts), (long)offsetof(struct cpArbiter, n),
        (long)offsetof(struct cpArbiter, state),
        (long)sizeof(cpContact), (long)offsetof(cpContact, r1), (long)offsetof(cpContact, r2),
        (long)offsetof(cpContact, tMass), (long)offsetof(cpContact, bounce), (long)offsetof(cpContact, jnAcc),
        (long)offsetof(cpContact, jtAcc), (long)offsetof(cpContact, hash),
        (long)sizeof(cpContactPointSet), (long)offsetof(cpContactPointSet, normal),
        (long)offsetof(cpContactPointSet, points), (long)sizeof(tm_point_pair),
        (long)sizeof(tm_handler), (long)offsetof(tm_handler, beginFunc), (long)offsetof(tm_handler, preSolveFunc),
        (long)offsetof(tm_handler, separateFunc), (long)offsetof(tm_handler, userData),
    };
    int m = (int)(sizeof(v) / sizeof(v[0]));
    for (int i = 0; i < m && i < n; i++) out[i] = v[i];
    return m;
}

/* ---------------------------------------------------------------------------------------- Python's arithmetic */

/* CPython's float % (float_rem): the remainder takes the sign of the divisor. */
double tm_py_mod(double vx, double wx) {
    double mod = fmod(vx, wx);
    if (mod) {
        if ((wx < 0) != (mod < 0)) mod += wx;
    } else {
        mod = copysign(0.0, wx);
    }
    return mod;
}

typedef struct { double hi, lo; } tm_dl;

static inline tm_dl tm_dl_mul(double x, double y) {
#ifdef TM_HYPOT_FMA /* CPython >= 3.12 */
    double hi = x * y;
    return (tm_dl){hi, fma(x, y, -hi)};
#else /* CPython 3.11: Dekker's mul12 */
    double t = x * 134217729.0, xh = t - (t - x), xl = x - xh;
    double u = y * 134217729.0, yh = u - (u - y), yl = y - yh;
    double p = xh * yh, q = xh * yl + xl * yh, z = p + q;
    return (tm_dl){z, p - z + q + xl * yl};
#endif
}

/* CPython's math.hypot(x, y) (vector_norm: correctly rounded in all but rare cases, and so not always libm's). */
double tm_py_hypot(double x, double y) {
    double v[2] = {fabs(x), fabs(y)};
    double mx = 0.0;
    for (int i = 0; i < 2; i++)
        if (v[i] > mx) mx = v[i];
    if (isinf(mx)) return mx;
    if (isnan(v[0]) || isnan(v[1])) return NAN;
    if (mx == 0.0) return mx;
    int e;
    frexp(mx, &e);
    if (e < -1023) return 2.2250738585072014e-308 * tm_py_hypot(v[0] / 2.2250738585072014e-308, v[1] / 2.2250738585072014e-308);
    double scale = ldexp(1.0, -e), csum = 1.0, frac1 = 0.0, frac2 = 0.0;
    for (int i = 0; i < 2; i++) {
        double a = v[i] * scale;
        tm_dl pr = tm_dl_mul(a, a);
        double s = csum + pr.hi;
        frac2 += (csum - s) + pr.hi;
        csum = s;
        frac1 += pr.lo;
    }
    double h = sqrt(csum - 1.0 + (frac1 + frac2));
    tm_dl pr = tm_dl_mul(-h, h);
    double s = csum + pr.hi;
    frac2 += (csum - s) + pr.hi;
    csum = s;
    frac1 += pr.lo;
    double r = csum - 1.0 + (frac1 + frac2);
    h += r / (2.0 * h);
    return h / scale;
}
