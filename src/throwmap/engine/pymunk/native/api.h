/* The Python-visible part of the engine's C helper: read by cffi as its cdef and included by the C sources.
   Plain declarations only (no macros, no includes): cffi parses this text. SI units throughout. */

typedef struct cpBody cpBody;
typedef struct cpShape cpShape;
typedef struct cpSpace cpSpace;
typedef struct cpArbiter cpArbiter;

/* One run's state shared between Python and C: the clock the collision callbacks read, the scene's geometry
   for the checks, the friction hook's and the exact solve's settings and counters. Allocated by tm_new. */
typedef struct tm_run {
    double now;          /* s, the time at the end of the step being taken (read by the Python callbacks) */
    int stop;            /* set by a Python callback: tm_steps returns after the current step */

    cpSpace *space;
    cpBody *arm;
    int n;               /* parts */
    cpBody **body;       /* [n] */
    cpShape **shape;     /* [n] */
    int *fell;           /* [n] 1 once the part has left the arm (taken out of the space) */
    double *verts;       /* part vertices about the CM, (x, y) pairs; part i's from vstart[i], vcount[i] of them */
    int *vstart, *vcount;
    double *R, *rho2;    /* [n] largest vertex distance from the CM (m), squared radius of gyration (m^2) */
    double *betas;       /* resting angles (rad); part i's from bstart[i], bcount[i] */
    int *bstart, *bcount;
    cpShape **others;    /* every shape part i can touch, from ostart[i], ocount[i] */
    int *ostart, *ocount;
    int *hasbox;         /* per entry of others: 1 if it has an arm-frame box */
    double *boxes;       /* per entry: (x0, x1, y0, y1), m */
    double *boxes_tol;   /* the same inflated by box_tol */
    double *corners;     /* arm-piece corners, arm frame, (x, y) pairs */
    int ncorners;
    int *hint;           /* [3 n] clearance hint per part: (kind, j, k), kind -1 none */
    double L, h, back, thick, margin, g, edge_eps, box_tol, settle_speed, settle_spin, arm_thickness;
    int plain_arm, end_wall;

    /* friction hook: 0 none, 1 one part on a bare arm, 2 one part with fixtures, 3 several parts */
    int hook;
    double cap;          /* CAP */
    double mu, mu_fix;   /* the pair's mu (inf allowed): arm, fixture */
    int fix;             /* collision type of fixture shapes */
    int by_u;            /* the arbiter's friction names the pair (u_arm/u_fix) */
    double u_arm, u_fix, unc_arm, unc_fix, mu_pp, unc_pp;
    double *inv_m, *inv_i;  /* [n] 1/m, 1/I of each part (several parts) */
    long n_capped;

    /* exact solve (one part) */
    int exact, armed, state_first, max_sweeps;
    double trigger, tol, same_point, mu_skid;
    long ex_steps, ex_sweeps, ex_unconverged, ex_fallback, ex_enumerated;
    int n_warm, cap_warm;
    void *warm;          /* owned by C (freed by tm_free) */

    /* the collision callbacks while attached (tm_attach .. tm_detach) */
    void *py;            /* handle of the run's Python contact bookkeeping (begin/separate), or NULL */
    void *handler;       /* the space's wildcard collision handler */
    void *saved[3];      /* its begin, pre-solve and separate functions before tm_attach */
} tm_run;

tm_run *tm_new(void);
void tm_free(tm_run *r);
int tm_bind(const char *name, void *fn);
int tm_layout(long *out, int n);
int tm_attach(tm_run *r, void *handler);
void tm_detach(tm_run *r);
int tm_contact_point(tm_run *r, cpArbiter *arb, int i, double *out);
double tm_py_hypot(double x, double y);
double tm_py_mod(double x, double y);
int tm_steps(tm_run *r, int n, double step, double *t);
int tm_steps_arm(tm_run *r, int n, double step, double *t, const double *angles, double arm_stop, double end_alpha,
                 double *rate);
void tm_probe(tm_run *r, int i, double horizon, int flips, double *out);
double tm_clearance(tm_run *r, int i, double enough);
double tm_vertex_speed_bound(tm_run *r);
void tm_leap(tm_run *r, double tau, double arm_angle);

