/* exp_anisotropy: E6 anisotropy attribution (design.md §7 E6; reference paper §5.4):
 * the commands anisotropy-lattice, anisotropy-hardcore, anisotropy-jitter,
 * anisotropy-jitter-calibrate and anisotropy-heldout. Every E6 unit runs the teacher at
 * beta_field, read from the E5 calibration table (--calibration).
 *
 * Stands as in E5 (exp_field.c; --layout 4m-on-36m: d = 4 m on 36 m, 5m-on-60m: 5 m on
 * 60 m; E6 varies only the stem process at that density and footprint),
 * teacher (--teacher) at N = 48, gamma = 1. Seeds: seed_derive(<seed experiment>, d, stand,
 * "stems"/"crowns"), one seed-experiment string per role, disjoint from E5's:
 *   anisotropy/lattice  E6 lattice statistic at beta_field
 *   anisotropy/hardcore hard-core family, same indices at every c
 *   anisotropy/jitter   jitter family (a* calibration), same indices at every a
 *   anisotropy/heldout  held-out stands at a*
 * Re-using the same indices across the levels of one sweep (common random
 * numbers) makes the sweep curves smooth in the knob without favouring any
 * level. Outputs: X.tsv and X_trees.tsv as in E5, summary written last.
 * Limits: d and L are fixed by the design; the levels come from
 * gates/anisotropy.gate (at most 32 per family); a hard-core level that
 * cannot be built is recorded, not a crash; stand counts are options. */
#include "exp_anisotropy.h"
#include "fieldrun.h"
#include "fieldsim.h"
#include "gate.h"
#include "paths.h"
#include "prov.h"
#include <stdio.h>
#include <string.h>

cs_status exp_anisotropy_lattice(const exp_field_opts *args)
{
    exp_field_opts o = *args;
    const int argc = args->argc;
    char **argv = args->argv;
    fs_calibration c;
    cs_status stb = fs_beta_field(o.calibration, &c);
    if (stb) return stb;
    prov p;
    exp_prov_begin(&p, "anisotropy", &o.rd, argc, argv);
    double a;
    cs_status st = fieldrun_canonical_jitter(&a);
    if (st) return st;
    fieldrun_job j = {.seed_exp = "anisotropy/lattice",
                      .kind = stems_lattice,
                      .shape = a,
                      .level = a,
                      .beta = c.value,
                      .nstands = o.stands,
                      .rd = o.rd};
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    st = fieldrun_run(&j, &acc, &worst);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"anisotropy/lattice\", %g, s, stems|crowns), s = 0..%u",
             exp_field_d(&o.rd), o.stands - 1);
    p.worst_overlap_m = worst;
    fieldrun_meta_ctx m = {c.value, a,
                           "E6 lattice: controlled lattice (layout in the layout line), canonical jitter (level = a), "
                           "teacher at beta_field"};
    if (!st) st = fieldrun_write(o.out, &p, &acc, &j, 1, fieldrun_meta_generic, &m);
    if (!st) {
        fs_summary s;
        if (!fs_group(&acc, 1, a, &s))
            printf("anisotropy-lattice: anisotropy median %.4f over %zu trees (%zu excluded) in %zu stands\n",
                   s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, s.stands);
    }
    fs_trees_free(&acc);
    return st;
}

/* A family sweep: one job per level of `key` in anisotropy.gate. */
static cs_status aniso_family(const char *cmd, const exp_field_opts *args, const stems_type *kind, const char *key,
                              const char *seed_exp, const char *what)
{
    exp_field_opts o = *args;
    const int argc = args->argc;
    char **argv = args->argv;
    fs_calibration c;
    cs_status stb = fs_beta_field(o.calibration, &c);
    if (stb) return stb;
    prov p;
    exp_prov_begin(&p, "anisotropy", &o.rd, argc, argv);
    double lv[32];
    size_t nl;
    cs_status st = gate_read_values(PATHS_GATE("anisotropy"), key, lv, 32, &nl);
    if (st) return st;
    fieldrun_job jobs[32];
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    for (size_t k = 0; k < nl && !st; k++) {
        jobs[k] = (fieldrun_job){.seed_exp = seed_exp,
                                 .kind = kind,
                                 .shape = lv[k],
                                 .level = lv[k],
                                 .beta = c.value,
                                 .nstands = o.stands,
                                 .rd = o.rd};
        st = fieldrun_run(&jobs[k], &acc, &worst);
        if (!st) {
            fs_summary s;
            if (jobs[k].failed == o.stands)
                fprintf(stderr, "%s: level %.2f UNBUILDABLE (%zu of %u stands failed)\n", cmd, lv[k], jobs[k].failed,
                        o.stands);
            else if (!fs_group(&acc, 1, lv[k], &s))
                fprintf(stderr, "%s: level %.2f: anisotropy median %.4f (%zu trees, %zu excluded; %zu stands failed)\n",
                        cmd, lv[k], s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, jobs[k].failed);
        }
    }
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"%s\", %g, s, stems|crowns), s = 0..%u at every level", seed_exp,
             exp_field_d(&o.rd), o.stands - 1);
    p.worst_overlap_m = worst;
    fieldrun_meta_ctx m = {c.value, 0, what};
    if (!st) st = fieldrun_write(o.out, &p, &acc, jobs, nl, fieldrun_meta_generic, &m);
    fs_trees_free(&acc);
    return st;
}

cs_status exp_anisotropy_hardcore(const exp_field_opts *o)
{
    return aniso_family("anisotropy-hardcore", o, stems_hardcore, "hardcore_levels", "anisotropy/hardcore",
                        "E6 hard-core family: n = (L/d)^2 stems, minimum distance c d (level = c), layout in the "
                        "layout line, teacher at beta_field");
}

cs_status exp_anisotropy_jitter(const exp_field_opts *o)
{
    return aniso_family(
        "anisotropy-jitter", o, stems_lattice, "jitter_levels", "anisotropy/jitter",
        "E6 jitter family: lattice (layout in the layout line), jitter sd a d (level = a), teacher at beta_field");
}

cs_status exp_anisotropy_jitter_calibrate(const exp_field_opts *args)
{
    exp_field_opts o = *args;
    const int argc = args->argc;
    char **argv = args->argv;
    prov p;
    exp_prov_begin(&p, "anisotropy", &o.rd, argc, argv);
    tsv *t;
    fs_trees tr;
    cs_status st = fs_load_checked(o.sweep, &t, &tr);
    if (st) return st;
    fs_trees_free(&tr);
    tsv_writer *w;
    if ((st = tsv_writer_open(&w, o.out))) { tsv_free(t); return st; }
    snprintf(p.seeds, sizeof p.seeds, "%s", tsv_meta(t, "seeds") ? tsv_meta(t, "seeds") : "-");
    p.worst_overlap_m = -1;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); tsv_free(t); return st; }
    tsv_writer_meta(w, "what",
                    "E6 jitter calibration curve: median anisotropy per jitter level (from %s); a* = interpolation to "
                    "the field median, rounded to 0.01 (fs_jitter_star)",
                    o.sweep);
    tsv_writer_columns(w, "level\taniso_median\taniso_trees");
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double lv, am;
        long n;
        const char *arm;
        if ((st = tsv_text(t, r, "arm", &arm))) break;
        if (strcmp(arm, "coupled")) continue;
        if ((st = tsv_double(t, r, "level", &lv)) || (st = tsv_double(t, r, "aniso_median", &am)) ||
            (st = tsv_long(t, r, "aniso_trees", &n)))
            break;
        tsv_writer_dbl(w, lv);
        tsv_writer_dbl(w, am);
        tsv_writer_long(w, n);
        tsv_writer_endrow(w);
    }
    tsv_free(t);
    if (st) { tsv_writer_abort(w); return st; }
    if ((st = tsv_writer_commit(w))) return st;
    fs_calibration c;
    if ((st = fs_jitter_star(o.out, &c))) return st;
    printf("anisotropy-jitter-calibrate: field median %.3f, a interpolated %.6f, a* %.2f%s\n", c.target, c.interp,
           c.value, c.bracketed ? "" : " (FIELD MEDIAN NOT BRACKETED by the sweep: nearest end)");
    return CS_OK;
}

cs_status exp_anisotropy_heldout(const exp_field_opts *args)
{
    exp_field_opts o = *args;
    const int argc = args->argc;
    char **argv = args->argv;
    fs_calibration c, js;
    cs_status stb = fs_beta_field(o.calibration, &c);
    if (stb) return stb;
    cs_status st = fs_jitter_star(o.jitter_calibration, &js);
    if (st) return st;
    prov p;
    exp_prov_begin(&p, "anisotropy", &o.rd, argc, argv);
    fieldrun_job j = {.seed_exp = "anisotropy/heldout",
                      .kind = stems_lattice,
                      .shape = js.value,
                      .level = js.value,
                      .beta = c.value,
                      .nstands = o.stands,
                      .rd = o.rd};
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    st = fieldrun_run(&j, &acc, &worst);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"anisotropy/heldout\", %g, s, stems|crowns), s = 0..%u",
             exp_field_d(&o.rd), o.stands - 1);
    p.worst_overlap_m = worst;
    fieldrun_meta_ctx m = {
        c.value, js.value,
        "E6 held-out at a*: lattice (layout in the layout line), jitter a* (level), teacher at beta_field"};
    if (!st) st = fieldrun_write(o.out, &p, &acc, &j, 1, fieldrun_meta_generic, &m);
    if (!st) {
        fs_summary s;
        if (!fs_group(&acc, 1, js.value, &s))
            printf("anisotropy-heldout: a* %.2f: anisotropy median %.4f (%zu trees, %zu excluded), elongation %.4f, "
                   "spread %.4f m; %zu of %u stands built\n",
                   js.value, s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, s.elong_median, s.f.spread,
                   s.stands, o.stands);
        fieldrun_print_spread_ratios("anisotropy-heldout", &acc, js.value, 0);
    }
    fs_trees_free(&acc);
    return st;
}
