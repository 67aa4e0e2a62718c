/* The exact contact solve of one part's steps where the friction cap would bind (throwmap.engine.pymunk.exact):
   the same Gauss-Seidel sweeps over the contacts, each the exact 2x2 Coulomb solve of one contact, in the same
   order and arithmetic. Where the sweeps cycle (MAX_SWEEPS), every combination of contact modes is tried by
   exact.enumerate_modes in Python (tm_enumerate), so that rare case is the same code as without the helper. */

static int tm_enumerate(void *py, int k, double *rows, double *u0, double m_inv, double i_inv, double scale,
                        double *out);

typedef struct tm_con {
    cpContact *c;
    cpArbiter *arb;
    double gn[3], gt[3], ann, ant, att, mu, en, et, jn, jt, rx, ry, own[3];
} tm_con;

typedef struct tm_warm { uintptr_t hash; double jn, jt; } tm_warm;

/* exact.solve_contact: the impulse (j_n, j_t) of one contact and its mode (0 separate, 1 stick, 2 slide, 3 none). */
static int tm_solve_contact(double wn, double wt, double ann, double ant, double att, double mu, double mu_skid,
                            double *jn_out, double *jt_out) {
    if (wn >= 0.0) {
        *jn_out = 0.0, *jt_out = 0.0;
        return 0;
    }
    double det = ann * att - ant * ant;
    double jn = (ant * wt - att * wn) / det;
    double jt = (ant * wn - ann * wt) / det;
    if (jn > 0.0 && fabs(jt) <= mu * jn) {
        *jn_out = jn, *jt_out = jt;
        return 1;
    }
    double m = mu <= mu_skid ? mu : mu_skid;
    double s0 = jt > 0.0 ? -1.0 : 1.0;
    for (int pass = 0; pass < 2; pass++) {
        double s = pass == 0 ? s0 : -s0;
        double d = ann - s * m * ant;
        if (d > 0.0) {
            jn = -wn / d;
            jt = -s * m * jn;
            double vt = wt + ant * jn + att * jt;
            if (s * vt >= 0.0) {
                *jn_out = jn, *jt_out = jt;
                return 2;
            }
        }
    }
    *jn_out = -wn / ann, *jt_out = 0.0;
    return 3;
}

/* exact._merge_points: contacts whose points on the part are within same_point act at their common (mean) point. */
static void tm_merge_points(tm_con *cons, int k, double m_inv, double i_inv, double same) {
    int group[k > 0 ? k : 1];
    for (int i = 0; i < k; i++) group[i] = i;
    for (int i = 0; i < k; i++)
        for (int j = i + 1; j < k; j++)
            if (fabs(cons[i].rx - cons[j].rx) < same && fabs(cons[i].ry - cons[j].ry) < same) {
                int gi = group[i], gj = group[j];
                if (gi != gj)
                    for (int m = 0; m < k; m++)
                        if (group[m] == gj) group[m] = gi;
            }
    for (int g = 0; g < k; g++) {
        int count = 0;
        double sx = 0.0, sy = 0.0; /* Python's sum(): left to right from 0 */
        for (int i = 0; i < k; i++)
            if (group[i] == g) {
                count++;
                sx += cons[i].rx, sy += cons[i].ry;
            }
        if (count < 2) continue;
        double rx = sx / count, ry = sy / count;
        for (int i = 0; i < k; i++) {
            if (group[i] != g) continue;
            tm_con *m = &cons[i];
            double nx = m->gn[0], ny = m->gn[1], tx = m->gt[0], ty = m->gt[1];
            m->gn[2] = rx * ny - ry * nx;
            m->gt[2] = rx * ty - ry * tx;
            double *gn = m->gn, *gt = m->gt;
            m->ann = m_inv * (gn[0] * gn[0] + gn[1] * gn[1]) + i_inv * gn[2] * gn[2];
            m->ant = m_inv * (gn[0] * gt[0] + gn[1] * gt[1]) + i_inv * gn[2] * gt[2];
            m->att = m_inv * (gt[0] * gt[0] + gt[1] * gt[1]) + i_inv * gt[2] * gt[2];
        }
    }
}

typedef struct { cpArbiter **arbs; int n, cap; } tm_found;

static void tm_collect(cpBody *body, cpArbiter *arb, void *data) {
    (void)body;
    tm_found *f = (tm_found *)data;
    if (f->n == f->cap) {
        int cap = f->cap ? 2 * f->cap : 16;
        cpArbiter **a = (cpArbiter **)realloc(f->arbs, (size_t)cap * sizeof(cpArbiter *));
        if (a == NULL) return;
        f->arbs = a, f->cap = cap;
    }
    f->arbs[f->n++] = arb;
}

static const tm_warm *tm_warm_get(tm_run *r, uintptr_t hash) {
    const tm_warm *w = (const tm_warm *)r->warm;
    for (int i = 0; i < r->n_warm; i++)
        if (w[i].hash == hash) return &w[i];
    return NULL;
}

/* ExactSolve._solve: this step's contacts of the part, solved with the pairs' true mu. */
static void tm_exact_solve(tm_run *r, cpBody *body, cpVect gravity, double dt) {
    tm_found found = {NULL, 0, 0};
    CP.cpBodyEachArbiter(body, tm_collect, &found);
    double m_inv = r->inv_m[0], i_inv = r->inv_i[0];
    cpVect v = CP.cpBodyGetVelocity(body);
    double vx = v.x, vy = v.y, w = CP.cpBodyGetAngularVelocity(body);
    int k = 0;
    for (int a = 0; a < found.n; a++) k += found.arbs[a]->count;
    tm_con stack[16], *cons = k <= 16 ? stack : (tm_con *)malloc((size_t)k * sizeof(tm_con));
    if (cons == NULL) {
        free(found.arbs);
        return;
    }
    k = 0;
    for (int a = 0; a < found.n; a++) {
        cpArbiter *arb = found.arbs[a];
        int part_b = arb->body_b == body;
        cpBody *other = part_b ? arb->body_a : arb->body_b;
        double s = part_b ? 1.0 : -1.0;
        double nx = arb->n.x, ny = arb->n.y, tx = -ny, ty = nx;
        double mu = (CP.cpShapeGetCollisionType(arb->a) == (uintptr_t)r->fix
                     || CP.cpShapeGetCollisionType(arb->b) == (uintptr_t)r->fix) ? r->mu_fix : r->mu;
        arb->u = isfinite(mu) ? mu : 1.0e30; /* (the hook may have capped it before the step was armed) */
        cpVect ov = CP.cpBodyGetVelocity(other);
        double ow = CP.cpBodyGetAngularVelocity(other);
        cpVect svr = arb->surface_vr;
        for (int i = 0; i < arb->count; i++) {
            cpContact *c = &arb->contacts[i];
            cpVect rr = part_b ? c->r2 : c->r1, ro = part_b ? c->r1 : c->r2;
            double rx = rr.x, ry = rr.y, ox = ro.x, oy = ro.y;
            double pvx = ov.x - oy * ow, pvy = ov.y + ox * ow;
            tm_con *q = &cons[k++];
            q->c = c, q->arb = arb;
            q->gn[0] = s * nx, q->gn[1] = s * ny, q->gn[2] = s * (rx * ny - ry * nx);
            q->gt[0] = s * tx, q->gt[1] = s * ty, q->gt[2] = s * (rx * ty - ry * tx);
            q->en = -s * (pvx * nx + pvy * ny) + svr.x * nx + svr.y * ny;
            q->et = -s * (pvx * tx + pvy * ty) + svr.x * tx + svr.y * ty;
            double *gn = q->gn, *gt = q->gt;
            q->ann = m_inv * (gn[0] * gn[0] + gn[1] * gn[1]) + i_inv * gn[2] * gn[2];
            q->ant = m_inv * (gn[0] * gt[0] + gn[1] * gt[1]) + i_inv * gn[2] * gt[2];
            q->att = m_inv * (gt[0] * gt[0] + gt[1] * gt[1]) + i_inv * gt[2] * gt[2];
            q->mu = mu, q->jn = 0.0, q->jt = 0.0, q->rx = rx, q->ry = ry;
            memcpy(q->own, q->gn, sizeof q->own);
        }
    }
    free(found.arbs);
    if (k == 0) return;
    if (k > 1) tm_merge_points(cons, k, m_inv, i_inv, r->same_point);
    r->ex_steps++;
    double ux = vx, uy = vy, uw = w;
    for (int i = 0; i < k; i++) {
        const tm_warm *x = tm_warm_get(r, cons[i].c->hash);
        if (x != NULL) {
            tm_con *q = &cons[i];
            q->jn = x->jn, q->jt = x->jt;
            ux += m_inv * (q->gn[0] * x->jn + q->gt[0] * x->jt);
            uy += m_inv * (q->gn[1] * x->jn + q->gt[1] * x->jt);
            uw += i_inv * (q->gn[2] * x->jn + q->gt[2] * x->jt);
        }
    }
    double scale = fabs(tm_py_hypot(gravity.x, gravity.y)) * dt / m_inv;
    int sweeps = 0, fallback = 0;
    for (;;) {
        sweeps++;
        double biggest = 0.0, change = 0.0;
        fallback = 0;
        for (int i = 0; i < k; i++) {
            tm_con *q = &cons[i];
            double *gn = q->gn, *gt = q->gt, jn0 = q->jn, jt0 = q->jt;
            double vn = gn[0] * ux + gn[1] * uy + gn[2] * uw + q->en;
            double vt = gt[0] * ux + gt[1] * uy + gt[2] * uw + q->et;
            double wn = vn - q->ann * jn0 - q->ant * jt0;
            double wt = vt - q->ant * jn0 - q->att * jt0;
            double jn, jt;
            int mode = tm_solve_contact(wn, wt, q->ann, q->ant, q->att, q->mu, r->mu_skid, &jn, &jt);
            double djn = jn - jn0, djt = jt - jt0;
            if (djn != 0.0 || djt != 0.0) {
                ux += m_inv * (gn[0] * djn + gt[0] * djt);
                uy += m_inv * (gn[1] * djn + gt[1] * djt);
                uw += i_inv * (gn[2] * djn + gt[2] * djt);
                q->jn = jn, q->jt = jt;
                if (fabs(djn) > change) change = fabs(djn);
                if (fabs(djt) > change) change = fabs(djt);
            }
            if (fabs(jn) > biggest) biggest = fabs(jn);
            if (fabs(jt) > biggest) biggest = fabs(jt);
            if (mode == 3) fallback = 1;
        }
        if (change <= r->tol * (biggest + scale)) break;
        if (sweeps >= r->max_sweeps) { /* a cycle: every combination of contact modes, in Python */
            double *rows = (double *)malloc((size_t)k * 11 * sizeof(double));
            double *out = (double *)malloc((size_t)k * 2 * sizeof(double));
            double u0[3] = {vx, vy, w};
            int ok = 0;
            if (rows != NULL && out != NULL) {
                for (int i = 0; i < k; i++) {
                    double *row = rows + 11 * i;
                    memcpy(row, cons[i].gn, 3 * sizeof(double));
                    memcpy(row + 3, cons[i].gt, 3 * sizeof(double));
                    row[6] = cons[i].mu, row[7] = cons[i].en, row[8] = cons[i].et, row[9] = cons[i].jn;
                    row[10] = cons[i].jt;
                }
                ok = tm_enumerate(r->py, k, rows, u0, m_inv, i_inv, biggest + scale, out);
            }
            if (!ok) {
                r->ex_unconverged++;
            } else {
                r->ex_enumerated++;
                fallback = 0;
                ux = vx, uy = vy, uw = w;
                for (int i = 0; i < k; i++) {
                    tm_con *q = &cons[i];
                    double jn = out[2 * i], jt = out[2 * i + 1];
                    q->jn = jn, q->jt = jt;
                    ux += m_inv * (q->gn[0] * jn + q->gt[0] * jt);
                    uy += m_inv * (q->gn[1] * jn + q->gt[1] * jt);
                    uw += i_inv * (q->gn[2] * jn + q->gt[2] * jt);
                }
            }
            free(rows);
            free(out);
            break;
        }
    }
    r->ex_sweeps += sweeps;
    if (fallback) r->ex_fallback++;
    CP.cpBodySetVelocity(body, (cpVect){ux, uy});
    CP.cpBodySetAngularVelocity(body, uw);
    if (r->cap_warm < k) {
        void *p = realloc(r->warm, (size_t)k * sizeof(tm_warm));
        if (p != NULL) r->warm = p, r->cap_warm = k;
    }
    tm_warm *warm = (tm_warm *)r->warm;
    r->n_warm = 0;
    for (int i = 0; i < k; i++) {
        tm_con *q = &cons[i];
        cpContact *c = q->c;
        q->arb->state = r->state_first; /* the impulses are in the velocities already: no warm start */
        c->jnAcc = q->jn, c->jtAcc = q->jt;
        c->tMass = 0.0; /* the friction impulse stays as solved */
        c->bounce = -(q->own[0] * ux + q->own[1] * uy + q->own[2] * uw + q->en);
        if (warm == NULL || i >= r->cap_warm) continue;
        int j = 0; /* a dict keyed by the contact's hash: a repeated hash keeps its place, takes the new value */
        while (j < r->n_warm && warm[j].hash != c->hash) j++;
        warm[j].hash = c->hash, warm[j].jn = q->jn, warm[j].jt = q->jt;
        if (j == r->n_warm) r->n_warm++;
    }
    if (cons != stack) free(cons);
}

/* The body's velocity update for an armed step: Chipmunk's own, then the exact solve; disarms itself. */
static void tm_velocity(cpBody *body, cpVect gravity, double damping, double dt) {
    tm_run *r = (tm_run *)CP.cpSpaceGetUserData(CP.cpBodyGetSpace(body));
    CP.cpBodyUpdateVelocity(body, gravity, damping, dt);
    CP.cpBodySetVelocityUpdateFunc(body, CP.cpBodyUpdateVelocity);
    if (r == NULL) return;
    r->armed = 0;
    tm_exact_solve(r, body, gravity, dt);
}
