/* The run loop's hot paths in C (throwmap.engine.pymunk.stepping and .checks): blocks of pymunk steps with the
   arm parked, and the per-part checks, with Python's arithmetic operation for operation (math.hypot as CPython
   computes it, float % as CPython's), so a run is the same bit for bit with or without the helper. */

/* stepping.fixed_steps with the arm parked: up to n steps of `step` (s) from *t; returns how many were taken
   (fewer where a Python callback set r->stop: the caller then does what the callback asked). */
int tm_steps(tm_run *r, int n, double step, double *t) {
    double tt = *t;
    for (int i = 0; i < n; i++) {
        double t_next = tt + step;
        r->now = t_next;
        CP.cpSpaceStep(r->space, step);
        tt = t_next;
        if (r->stop) {
            r->stop = 0;
            *t = tt;
            return i + 1;
        }
    }
    *t = tt;
    return n;
}

/* stepping.fixed_steps with the arm moving (or stopping): up to n steps of `step` (s) from *t. While t < arm_stop the
   arm is put at angles[j] (rad, alpha + theta(t_j): the angles at the block's step times t_0 = *t, t_{j+1} = t_j +
   step, as far as the arm moves) turning at the rate that takes it to angles[j + 1] in the step; once t >= arm_stop
   it is parked at end_alpha, at rest (once). *rate: the arm's rate as last set (rad/s, in and out). Returns the
   steps taken (fewer where a Python callback set r->stop). */
int tm_steps_arm(tm_run *r, int n, double step, double *t, const double *angles, double arm_stop, double end_alpha,
                 double *rate) {
    double tt = *t, wa = *rate;
    int moving = tt < arm_stop, j = 0, i = 0;
    while (i < n) {
        double t_next = tt + step;
        if (moving) {
            double a_now = angles[j], a_next = angles[j + 1];
            j++;
            CP.cpBodySetAngle(r->arm, a_now);
            wa = (a_next - a_now) / step;
            CP.cpBodySetAngularVelocity(r->arm, wa);
            moving = t_next < arm_stop;
        } else if (wa != 0.0) {
            CP.cpBodySetAngle(r->arm, end_alpha);
            CP.cpBodySetAngularVelocity(r->arm, 0.0);
            wa = 0.0;
        }
        r->now = t_next;
        CP.cpSpaceStep(r->space, step);
        tt = t_next;
        i++;
        if (r->stop) {
            r->stop = 0;
            break;
        }
    }
    *t = tt, *rate = wa;
    return i;
}

/* checks.escape as a code: 0 on the arm, 1 behind the joint, 2 off the end. */
static int tm_escape(tm_run *r, int i, double xa, double ya, int over) {
    if (r->end_wall && over > 0) over = 0; /* a vertex pressed into the wall's foot (run.py) */
    if (over) return over < 0 ? 1 : 2;
    double R = r->R[i], L = r->L, h = r->h;
    if (ya < h - r->arm_thickness - 3.0 * R || (ya < h && (xa < -r->back - R || xa > L + R))) return xa < 0.5 * L ? 1 : 2;
    return 0;
}

/* Part i's state and checks at one instant (the arm at its angle now), into out[17]: x, y, angle, vx, vy, spin
   (world frame); then
   checks.inspect's (depth, x_arm, y_arm, phi, over, near); checks.energy (J/kg); 1 if slower than the settling
   speed and spin; with `flips`, contacts.nearest_side's (side, tilt) of phi (else 0, 0); the escape code. */
void tm_probe(tm_run *r, int i, double horizon, int flips, double *out) {
    double arm_angle = CP.cpBodyGetAngle(r->arm), ca = cos(arm_angle), sa = sin(arm_angle);
    cpBody *b = r->body[i];
    cpVect p = CP.cpBodyGetPosition(b);
    double a = CP.cpBodyGetAngle(b);
    cpVect v = CP.cpBodyGetVelocity(b);
    double om = CP.cpBodyGetAngularVelocity(b);
    double px = p.x, py = p.y, vx = v.x, vy = v.y;
    double deepest = 0.0, L = r->L, h = r->h, back = r->back, thick = r->thick, margin = r->margin;
    double eps = r->edge_eps;
    int over = 0, near = 0;
    double c = cos(a), s = sin(a);
    const double *wv = r->verts + 2 * r->vstart[i];
    int nv = r->vcount[i];
    if (r->plain_arm) {
        for (int k = 0; k < nv; k++) {
            double wx = wv[2 * k], wy = wv[2 * k + 1];
            double X = px + c * wx - s * wy;
            double Y = py + s * wx + c * wy;
            double xa = ca * X + sa * Y;
            double ya = -sa * X + ca * Y;
            double d = h - ya;
            if (d > eps && (xa < -back || xa > L)) over = xa < -back ? -1 : 1;
            if (-back <= xa && xa <= L && d <= thick) {
                if (d > deepest) deepest = d;
                if (horizon > 0.0 && d < -eps) {
                    double vn = -sa * (vx - om * (Y - py)) + ca * (vy + om * (X - px));
                    double approach = -vn > 0.0 ? -vn : 0.0;
                    if (-d < margin + approach * horizon) near = 1;
                }
            }
        }
    } else {
        double lo = -back - eps, hi = L + eps;
        int o0 = r->ostart[i], no = r->ocount[i];
        double reach = 0.0;
        if (horizon > 0.0) reach = margin + (tm_py_hypot(vx, vy) + fabs(om) * r->R[i]) * horizon + r->box_tol;
        for (int k = 0; k < nv; k++) {
            double wx = wv[2 * k], wy = wv[2 * k + 1];
            double X = px + c * wx - s * wy;
            double Y = py + s * wx + c * wy;
            double xa = ca * X + sa * Y;
            double ya = -sa * X + ca * Y;
            if (h - ya > eps && (xa < lo || xa > hi)) over = xa < lo ? -1 : 1;
            int queried = 0;
            cpVect q = {0.0, 0.0};
            double closest = INFINITY;
            for (int j = 0; j < no; j++) {
                int e = o0 + j;
                if (r->hasbox[e]) {
                    double x0, x1, y0, y1;
                    if (horizon > 0.0) {
                        const double *bx = r->boxes + 4 * e;
                        x0 = bx[0] - reach, x1 = bx[1] + reach, y0 = bx[2] - reach, y1 = bx[3] + reach;
                    } else {
                        const double *bx = r->boxes_tol + 4 * e;
                        x0 = bx[0], x1 = bx[1], y0 = bx[2], y1 = bx[3];
                    }
                    if (xa < x0 || xa > x1 || ya < y0 || ya > y1) continue;
                }
                if (!queried) {
                    q = CP.cpBodyLocalToWorld(b, (cpVect){wx, wy});
                    queried = 1;
                }
                double d = CP.cpShapePointQuery(r->others[e], q, NULL);
                if (d < -deepest) deepest = -d;
                if (d < closest) closest = d;
            }
            if (queried && horizon > 0.0 && eps < closest) {
                double speed = tm_py_hypot(vx - om * (q.y - py), vy + om * (q.x - px));
                if (closest < margin + speed * horizon) near = 1;
            }
        }
    }
    out[0] = px, out[1] = py, out[2] = a, out[3] = vx, out[4] = vy, out[5] = om;
    out[6] = deepest, out[7] = ca * px + sa * py, out[8] = -sa * px + ca * py, out[9] = a - arm_angle;
    out[10] = over, out[11] = near;
    out[12] = 0.5 * (vx * vx + vy * vy + r->rho2[i] * om * om) + r->g * py;
    out[13] = tm_py_hypot(vx, vy) < r->settle_speed && fabs(om) < r->settle_spin;
    out[14] = 0.0, out[15] = 0.0;
    if (flips) {
        double phi = out[9], best = INFINITY;
        int kb = 0;
        const double *betas = r->betas + r->bstart[i];
        for (int k = 0; k < r->bcount[i]; k++) {
            double d = tm_py_mod(phi - betas[k] + 3.141592653589793, 2.0 * 3.141592653589793) - 3.141592653589793;
            if (fabs(d) < fabs(best)) best = d, kb = k;
        }
        out[14] = kb, out[15] = best;
    }
    out[16] = tm_escape(r, i, out[7], out[8], over);
}

static inline double tm_distance(cpShape *s, cpVect p) { return CP.cpShapePointQuery(s, p, NULL); }

static inline cpVect tm_vertex(tm_run *r, int part, int k) {
    const double *wv = r->verts + 2 * (r->vstart[part] + k);
    return CP.cpBodyLocalToWorld(r->body[part], (cpVect){wv[0], wv[1]});
}

/* checks.clearance: a lower bound of the distance (m) from part i to every other shape, with its hint. */
double tm_clearance(tm_run *r, int i, double enough) {
    cpShape *shp = r->shape[i];
    int *hint = r->hint + 3 * i;
    int o0 = r->ostart[i], no = r->ocount[i];
    if (hint[0] >= 0) {
        double d;
        int j = hint[1], k = hint[2];
        if (hint[0] == 0) {
            d = tm_distance(r->others[o0 + j], tm_vertex(r, i, k));
        } else if (hint[0] == 1) {
            double aa = CP.cpBodyGetAngle(r->arm), cx = r->corners[2 * k], cy = r->corners[2 * k + 1];
            d = tm_distance(shp, (cpVect){cos(aa) * cx - sin(aa) * cy, sin(aa) * cx + cos(aa) * cy});
        } else {
            d = tm_distance(shp, tm_vertex(r, j, k));
        }
        if (d <= enough) return d;
    }
    double best = INFINITY;
    int hk = hint[0], hj = hint[1], hv = hint[2];
    for (int k = 0; k < r->vcount[i]; k++) {
        cpVect v = tm_vertex(r, i, k);
        for (int j = 0; j < no; j++) {
            double d = tm_distance(r->others[o0 + j], v);
            if (d < best) best = d, hk = 0, hj = j, hv = k;
        }
    }
    double aa = CP.cpBodyGetAngle(r->arm), ca = cos(aa), sa = sin(aa);
    for (int k = 0; k < r->ncorners; k++) {
        double cx = r->corners[2 * k], cy = r->corners[2 * k + 1];
        double d = tm_distance(shp, (cpVect){ca * cx - sa * cy, sa * cx + ca * cy});
        if (d < best) best = d, hk = 1, hj = 0, hv = k;
    }
    for (int j = 0; j < r->n; j++) {
        if (j == i) continue;
        for (int k = 0; k < r->vcount[j]; k++) {
            double d = tm_distance(shp, tm_vertex(r, j, k));
            if (d < best) best = d, hk = 2, hj = j, hv = k;
        }
    }
    hint[0] = hk, hint[1] = hj, hint[2] = hv;
    return best;
}

/* stepping.vertex_speed_bound: the largest CM speed plus spin x reach over the parts still on the arm, m/s. */
double tm_vertex_speed_bound(tm_run *r) {
    double vmax = 0.0;
    for (int i = 0; i < r->n; i++) {
        if (r->fell[i]) continue;
        cpVect v = CP.cpBodyGetVelocity(r->body[i]);
        double x = tm_py_hypot(v.x, v.y) + fabs(CP.cpBodyGetAngularVelocity(r->body[i])) * r->R[i];
        if (x > vmax) vmax = x;
    }
    return vmax;
}

/* stepping.leap: every part along its exact parabola for tau (s); the arm at arm_angle (rad), at rest. */
void tm_leap(tm_run *r, double tau, double arm_angle) {
    double g = r->g;
    for (int i = 0; i < r->n; i++) {
        cpBody *b = r->body[i];
        cpVect p = CP.cpBodyGetPosition(b), v = CP.cpBodyGetVelocity(b);
        double px = p.x, py = p.y, vx = v.x, vy = v.y;
        CP.cpBodySetPosition(b, (cpVect){px + vx * tau, py + vy * tau - 0.5 * g * tau * tau});
        CP.cpBodySetVelocity(b, (cpVect){vx, vy - g * tau});
        CP.cpBodySetAngle(b, CP.cpBodyGetAngle(b) + CP.cpBodyGetAngularVelocity(b) * tau);
    }
    CP.cpBodySetAngle(r->arm, arm_angle);
    CP.cpBodySetAngularVelocity(r->arm, 0.0);
    CP.cpSpaceReindexShapesForBody(r->space, r->arm);
    /* the parts' cached world vertices too: the clearance measures corners and other parts against them */
    for (int i = 0; i < r->n; i++) CP.cpSpaceReindexShapesForBody(r->space, r->body[i]);
}
