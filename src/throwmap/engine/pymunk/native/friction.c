/* The friction hook (Chipmunk's pre-solve) in C: the arithmetic of throwmap.engine.pymunk.friction's raw hooks,
   operation for operation, so the friction set on each arbiter is the same bit for bit.

   Each contact's friction becomes min(mu, CAP K_nn / |K_nt|) over the arbiter's contacts (one part: per unit
   mass K_nn = 1 + r_n^2/rho^2, K_nt = r_n r_t/rho^2); where the cap binds on one part and its previous impulses
   came near it, the step is solved exactly instead (exact.c). The run is found from the space's user data. */

static void tm_velocity(cpBody *body, cpVect gravity, double damping, double dt);

tm_run *tm_new(void) {
    tm_run *r = (tm_run *)calloc(1, sizeof(tm_run));
    return r;
}

void tm_free(tm_run *r) {
    if (r == NULL) return;
    free(r->warm);
    free(r);
}

static void tm_presolve(cpArbiter *arb, cpSpace *space, void *data);
static void tm_py_begin(void *py, cpArbiter *arb, int ia, int ib);
static void tm_py_separate(void *py, int ia, int ib);

static int tm_part_index(tm_run *r, cpBody *b) {
    for (int i = 0; i < r->n; i++)
        if (r->body[i] == b) return i;
    return -1;
}

/* Begin and separate: the part indices of the arbiter's bodies (-1: not a part), handed to the run's Python
   bookkeeping (contacts.Contacts); a separation because a shape was removed is not one. */
static void tm_begin(cpArbiter *arb, cpSpace *space, void *data) {
    (void)data;
    tm_run *r = (tm_run *)CP.cpSpaceGetUserData(space);
    if (r == NULL || r->py == NULL) return;
    cpBody *a, *b;
    CP.cpArbiterGetBodies(arb, &a, &b);
    tm_py_begin(r->py, arb, tm_part_index(r, a), tm_part_index(r, b));
}

static void tm_separate(cpArbiter *arb, cpSpace *space, void *data) {
    (void)data;
    tm_run *r = (tm_run *)CP.cpSpaceGetUserData(space);
    if (r == NULL || r->py == NULL || CP.cpArbiterIsRemoval(arb)) return;
    cpBody *a, *b;
    CP.cpArbiterGetBodies(arb, &a, &b);
    tm_py_separate(r->py, tm_part_index(r, a), tm_part_index(r, b));
}

/* The first contact point of `arb` on part i, into out[2] (m, world frame); 0 where the arbiter has none. */
int tm_contact_point(tm_run *r, cpArbiter *arb, int i, double *out) {
    cpContactPointSet cps = CP.cpArbiterGetContactPointSet(arb);
    if (cps.count <= 0) return 0;
    cpShape *a, *b;
    CP.cpArbiterGetShapes(arb, &a, &b);
    cpVect p = CP.cpShapeGetBody(a) == r->body[i] ? cps.points[0].pointA : cps.points[0].pointB;
    out[0] = p.x, out[1] = p.y;
    return 1;
}

/* Make `r` the space's user data and, on the wildcard collision `handler`, the C friction hook its pre-solve (where
   r->hook is set) and the C begin/separate its callbacks (where r->py is set). tm_detach undoes it: the run's C
   state is only reached from the space while the run is in progress. */
int tm_attach(tm_run *r, void *handler) {
    if (r->space == NULL || handler == NULL) return -1;
    tm_handler *h = (tm_handler *)handler;
    r->handler = handler;
    r->saved[0] = h->beginFunc, r->saved[1] = h->preSolveFunc, r->saved[2] = h->separateFunc;
    CP.cpSpaceSetUserData(r->space, r);
    if (r->hook) h->preSolveFunc = (void *)tm_presolve;
    if (r->py != NULL) h->beginFunc = (void *)tm_begin, h->separateFunc = (void *)tm_separate;
    return 0;
}

void tm_detach(tm_run *r) {
    if (r->handler == NULL) return;
    tm_handler *h = (tm_handler *)r->handler;
    h->beginFunc = r->saved[0], h->preSolveFunc = r->saved[1], h->separateFunc = r->saved[2];
    CP.cpSpaceSetUserData(r->space, NULL);
    r->handler = NULL;
    r->py = NULL;
}

/* Whether the step needs the exact solve at friction cap `cap`: a contact is new or did not push, or its friction
   ratio exceeded trigger x cap (exact.ExactSolve.wanted). */
static int tm_wanted(tm_run *r, cpArbiter *arb, double cap) {
    double lim = r->trigger * cap;
    for (int i = 0; i < arb->count; i++) {
        cpContact *c = &arb->contacts[i];
        double jn = c->jnAcc;
        if (jn <= 0.0 || fabs(c->jtAcc) > lim * jn) return 1;
    }
    return 0;
}

static void tm_arm(tm_run *r) {
    if (!r->armed) {
        r->armed = 1;
        CP.cpBodySetVelocityUpdateFunc(r->body[0], tm_velocity);
    }
}

static inline double tm_uncapped(double mu) { return isfinite(mu) ? mu : 1.0e30; }

/* One part: friction.set_capped with the part's points A or B. */
static void tm_set_capped(tm_run *r, cpArbiter *arb, int point_b, double mu) {
    cpVect n = CP.cpArbiterGetNormal(arb);
    double nx = n.x, ny = n.y;
    cpVect q = CP.cpBodyGetPosition(r->body[0]);
    double rho2 = r->rho2[0], cap = INFINITY;
    int count = CP.cpArbiterGetCount(arb);
    for (int i = 0; i < count; i++) {
        cpVect p = point_b ? CP.cpArbiterGetPointB(arb, i) : CP.cpArbiterGetPointA(arb, i);
        double rx = p.x - q.x, ry = p.y - q.y;
        double rn = rx * ny - ry * nx;
        double rt = rx * nx + ry * ny;
        if (rn * rt != 0.0) {
            double v = r->cap * (rho2 + rn * rn) / fabs(rn * rt);
            if (v < cap) cap = v;
        }
    }
    if (cap < mu) {
        r->n_capped++;
        if (!r->exact || !tm_wanted(r, arb, cap)) {
            CP.cpArbiterSetFriction(arb, cap);
        } else {
            tm_arm(r);
            CP.cpArbiterSetFriction(arb, tm_uncapped(mu));
        }
    } else {
        CP.cpArbiterSetFriction(arb, tm_uncapped(mu));
    }
}

/* One part with fixtures, μ from the shapes' collision types (friction._SinglePartFixtureCap._slow). */
static void tm_fixture_slow(tm_run *r, cpArbiter *arb) {
    cpShape *a, *b;
    CP.cpArbiterGetShapes(arb, &a, &b);
    double mu = (CP.cpShapeGetCollisionType(a) == (uintptr_t)r->fix || CP.cpShapeGetCollisionType(b) == (uintptr_t)r->fix)
        ? r->mu_fix : r->mu;
    tm_set_capped(r, arb, CP.cpShapeGetBody(a) != r->body[0], mu);
}

/* The pair named by the arbiter's friction (the product of its shapes'); 0 where it names none. */
static int tm_by_u(tm_run *r, double u, double *mu, double *unc) {
    if (u == r->u_fix) {
        *mu = r->mu_fix, *unc = r->unc_fix;
        return 1;
    }
    if (u == r->u_arm) {
        *mu = r->mu, *unc = r->unc_arm;
        return 1;
    }
    return 0;
}

/* One part with fixtures (friction._SinglePartFixtureCap's fast path). */
static void tm_fixture(tm_run *r, cpArbiter *arb) {
    double mu, unc;
    double u = CP.cpArbiterGetFriction(arb);
    if (!r->by_u || !tm_by_u(r, u, &mu, &unc)) {
        tm_fixture_slow(r, arb);
        return;
    }
    cpBody *ba, *bb;
    CP.cpArbiterGetBodies(arb, &ba, &bb);
    int part_a = ba == r->body[0];
    cpContactPointSet cps = CP.cpArbiterGetContactPointSet(arb);
    double nx = cps.normal.x, ny = cps.normal.y;
    cpVect q = CP.cpBodyGetPosition(r->body[0]);
    double qx = q.x, qy = q.y, rho2 = r->rho2[0], cap = INFINITY;
    for (int i = 0; i < cps.count; i++) {
        cpVect p = part_a ? cps.points[i].pointA : cps.points[i].pointB;
        double rx = p.x - qx, ry = p.y - qy;
        double rn = rx * ny - ry * nx;
        double rt = rx * nx + ry * ny;
        if (rn * rt != 0.0) {
            double v = r->cap * (rho2 + rn * rn) / fabs(rn * rt);
            if (v < cap) cap = v;
        }
    }
    if (cap < mu) {
        r->n_capped++;
        if (!r->exact || !tm_wanted(r, arb, cap)) {
            CP.cpArbiterSetFriction(arb, cap);
        } else {
            tm_arm(r);
            if (unc != u) CP.cpArbiterSetFriction(arb, unc);
        }
    } else if (unc != u) {
        CP.cpArbiterSetFriction(arb, unc);
    }
}

/* Several parts (friction._MultiPartCap): part-part pairs take mu_pp, the others the arm's or the fixture's mu. */
static void tm_multi(tm_run *r, cpArbiter *arb) {
    cpBody *ba, *bb;
    CP.cpArbiterGetBodies(arb, &ba, &bb);
    int ia = tm_part_index(r, ba), ib = tm_part_index(r, bb);
    double mu, unc;
    if (ia >= 0 && ib >= 0) {
        mu = r->mu_pp, unc = r->unc_pp;
    } else {
        if (ia < 0 && ib < 0) return;
        if (!r->by_u || !tm_by_u(r, CP.cpArbiterGetFriction(arb), &mu, &unc)) {
            cpShape *sa, *sb;
            CP.cpArbiterGetShapes(arb, &sa, &sb);
            if (CP.cpShapeGetCollisionType(sa) == (uintptr_t)r->fix || CP.cpShapeGetCollisionType(sb) == (uintptr_t)r->fix)
                mu = r->mu_fix, unc = r->unc_fix;
            else
                mu = r->mu, unc = r->unc_arm;
        }
        if (mu == 0.0) return; /* never capped, and the arbiter already holds 0 */
    }
    cpContactPointSet cps = CP.cpArbiterGetContactPointSet(arb);
    double nx = cps.normal.x, ny = cps.normal.y, cap = INFINITY;
    if (ia < 0 || ib < 0) { /* a part and the arm: one body's terms */
        int on_a = ib < 0, k = on_a ? ia : ib;
        cpVect q = CP.cpBodyGetPosition(on_a ? ba : bb);
        double qx = q.x, qy = q.y, m0 = r->inv_m[k], m1 = r->inv_i[k];
        for (int i = 0; i < cps.count; i++) {
            cpVect p = on_a ? cps.points[i].pointA : cps.points[i].pointB;
            double rx = p.x - qx, ry = p.y - qy;
            double rn = rx * ny - ry * nx;
            double knt = rn * (rx * nx + ry * ny) * m1;
            if (knt != 0.0) {
                double v = r->cap * (m0 + rn * rn * m1) / fabs(knt);
                if (v < cap) cap = v;
            }
        }
    } else {
        cpVect qa = CP.cpBodyGetPosition(ba), qb = CP.cpBodyGetPosition(bb);
        for (int i = 0; i < cps.count; i++) {
            double knn = 0.0, knt = 0.0;
            cpVect p = cps.points[i].pointA;
            double rx = p.x - qa.x, ry = p.y - qa.y;
            double rn = rx * ny - ry * nx, rt = rx * nx + ry * ny;
            knn += r->inv_m[ia] + rn * rn * r->inv_i[ia];
            knt += rn * rt * r->inv_i[ia];
            p = cps.points[i].pointB;
            rx = p.x - qb.x, ry = p.y - qb.y;
            rn = rx * ny - ry * nx, rt = rx * nx + ry * ny;
            knn += r->inv_m[ib] + rn * rn * r->inv_i[ib];
            knt += rn * rt * r->inv_i[ib];
            if (knt != 0.0) {
                double v = r->cap * knn / fabs(knt);
                if (v < cap) cap = v;
            }
        }
    }
    if (cap < mu) {
        r->n_capped++;
        CP.cpArbiterSetFriction(arb, cap);
    } else {
        CP.cpArbiterSetFriction(arb, unc);
    }
}

static void tm_presolve(cpArbiter *arb, cpSpace *space, void *data) {
    (void)data;
    tm_run *r = (tm_run *)CP.cpSpaceGetUserData(space);
    if (r == NULL) return;
    switch (r->hook) {
    case 1: tm_set_capped(r, arb, 0, r->mu); break;
    case 2: tm_fixture(r, arb); break;
    case 3: tm_multi(r, arb); break;
    default: break;
    }
}
