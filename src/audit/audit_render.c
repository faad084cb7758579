/* audit_render: the write-up read as TeX renders it, with every generated
 * value hidden (design.md §9, audit/README.md). numbers.tex and constants.tex
 * are written in their hidden form (the same macros, each printing one word;
 * a branch prints both its sides; counters and page numbers hidden), every
 * other generated file as that word, into build/render/paper/. pdflatex
 * renders paper/main.tex there: a generated file's name resolves to its hidden
 * form first, a hand-written one to paper/. pdftotext reads the PDF back, and
 * the rendered text may hold no digit outside the names of render_names[] and
 * no verdict word. So whatever a definition trick, an inclusion or a branch
 * makes TeX print is read as the reader would read it. Not seen: a number
 * written out in words, and text that tells the render from the real build
 * (the static reading, audit_tex.c, refuses the means it knows of). */
#include "audit_render.h"
#include "audit_paper.h"
#include "afile.h"
#include <ctype.h>
#include <errno.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Names that hold a digit and no quantity: the study's experiments, the
 * Wasserstein-1 distance (W1), instruction sets, a hash's name and the
 * simulation's two versions. A whole word
 * must equal one of them (trailing punctuation aside). */
static const char *const render_names[] = {"E0",   "E1",      "E2",      "E3",        "E4",        "E5",
                                           "E6",   "E7",      "E8",      "E9",        "W1",        "Wasserstein-1",
                                           "AVX2", "AVX-512", "SHA-256", "teacher-1", "teacher-2", NULL};

/* The words a verdict prints as (\verdict's output, the gate files' and
 * make verify's), in any case; the rendered text holds none: a verdict prints
 * through \verdict from a gate macro, hidden in the render. */
static const char *const verdict_words[] = {"pass", "fail", "pending", "notrep", NULL};

static int render_name(const char *w)
{
    for (int i = 0; render_names[i]; i++) if (!strcmp(render_names[i], w)) return 1;
    return 0;
}

static int verdict_word(const char *w)
{
    char low[64];
    size_t k = 0;
    for (; w[k] && k + 1 < sizeof low; k++) low[k] = (char)tolower((unsigned char)w[k]);
    low[k] = '\0';
    for (int i = 0; verdict_words[i]; i++) if (!strcmp(verdict_words[i], low)) return 1;
    return 0;
}

/* Strip what surrounds a word in running text: brackets, quotes and
 * sentence punctuation (ASCII and the UTF-8 quotes pdftotext writes). */
static void word_trim(char *w)
{
    static const char *const outer[] = {"\xe2\x80\x9c", "\xe2\x80\x9d", "\xe2\x80\x98", "\xe2\x80\x99", NULL};
    for (int again = 1; again;) {
        again = 0;
        size_t n = strlen(w);
        if (n && strchr("()[]{},;:.!?\"'", w[n - 1])) { w[n - 1] = '\0'; again = 1; continue; }
        if (w[0] && strchr("()[]{}\"'", w[0])) { memmove(w, w + 1, n); again = 1; continue; }
        for (int i = 0; outer[i]; i++) {
            size_t q = strlen(outer[i]);
            if (n >= q && !strcmp(w + n - q, outer[i])) { w[n - q] = '\0'; again = 1; break; }
            if (!strncmp(w, outer[i], q)) { memmove(w, w + q, n - q + 1); again = 1; break; }
        }
    }
}

size_t render_scan_text(const char *text, const char *what, checklist *cl)
{
    size_t bad = 0;
    int page = 1;
    for (const char *s = text; *s;) {
        if (*s == '\f') { page++; s++; continue; }
        if (isspace((unsigned char)*s)) { s++; continue; }
        const char *b = s;
        while (*s && !isspace((unsigned char)*s) && *s != '\f') s++;
        char w[128];
        snprintf(w, sizeof w, "%.*s", (int)(s - b), b);
        word_trim(w);
        int digit = strpbrk(w, "0123456789") != NULL;
        if (!(digit && !render_name(w)) && !verdict_word(w)) continue;
        /* the line it stands on, for the reader to find it */
        const char *l0 = b, *l1 = s;
        while (l0 > text && l0[-1] != '\n' && l0[-1] != '\f') l0--;
        while (*l1 && *l1 != '\n' && *l1 != '\f') l1++;
        checklist_add(cl, VERDICT_FAIL, "paper render",
                      "%s renders %s '%s' on page %d of the hidden render: '%.*s' (a generated value, verdict or "
                      "design constant prints through its macro; nothing else of the text may)",
                      what, digit ? "the number" : "the verdict word", w, page, (int)(l1 - l0 > 160 ? 160 : l1 - l0),
                      l0);
        bad++;
    }
    return bad;
}

/* build/render/paper emptied (files only: the render writes no folders). */
static cs_status render_dir(const char *dir)
{
    if (afile_mkdir_parents(dir) || (mkdir(dir, 0777) && errno != EEXIST))
        return cs_err(CS_EIO, "%s: cannot create (%s)", dir, strerror(errno));
    DIR *d = opendir(dir);
    if (!d) return cs_err(CS_EIO, "%s: cannot open (%s)", dir, strerror(errno));
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char p[600];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    closedir(d);
    return CS_OK;
}

/* The first TeX error of the render's log and the input line it names. */
static void render_error(const char *log, char *out, size_t n)
{
    char *text = afile_read(log);
    snprintf(out, n, "see %s", log);
    if (!text) return;
    char *e = strstr(text, "\n! ");
    if (e) {
        char *l = strstr(e, "\nl.");
        int el = (int)strcspn(e + 1, "\n"), ll = l ? (int)strcspn(l + 1, "\n") : 0;
        snprintf(out, n, "%.*s%s%.*s (%s)", el > 200 ? 200 : el, e + 1, l ? " at " : "", ll > 120 ? 120 : ll,
                 l ? l + 1 : "", log);
    }
    free(text);
}

int render_tools_present(void)
{
    return system("command -v pdflatex >/dev/null 2>&1 && command -v pdftotext >/dev/null 2>&1") == 0;
}

void audit_render(const claims *c, const claim_result *res, checklist *cl)
{
    const char *dir = PATHS_RENDER_DIR;
    char root[1024], p[1200];
    size_t before = cl->n;
    cs_status st = getcwd(root, sizeof root) ? render_dir(dir) : cs_err(CS_EIO, "getcwd: %s", strerror(errno));
    snprintf(p, sizeof p, "%s/numbers.tex", dir);
    if (!st) st = claims_write_numbers(p, c, res, 1);
    snprintf(p, sizeof p, "%s/constants.tex", dir);
    if (!st) st = audit_write_constants(p, 1);
    for (size_t i = 0; !st && paper_generated(i); i++) {
        const char *name = strrchr(paper_generated(i), '/') + 1;
        if (!strcmp(name, "numbers.tex") || !strcmp(name, "constants.tex") || !strstr(name, ".tex")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, name);
        afile a;
        if (!(st = afile_open(&a, p))) { fprintf(a.f, "\\hiddenvalue{}\n"); st = afile_commit(&a); }
    }
    if (st) {
        checklist_add(cl, VERDICT_FAIL, "paper render", "cannot write the hidden generated files: %s", cs_errmsg());
        return;
    }
    /* TEXINPUTS: the hidden files, then paper/'s hand-written ones; no shell;
     * a job name of its own, so the real build's main.aux (its resolved
     * references) is not read: references print as ?? */
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && TEXINPUTS='.:%s/" PATHS_PAPER_DIR
             ":' openout_any=p pdflatex -no-shell-escape -interaction=nonstopmode -halt-on-error -jobname=hidden "
             "'%s/" PATHS_MAIN_TEX "' > render.out 2>&1"
             " && pdftotext -enc UTF-8 hidden.pdf hidden.txt 2>> render.out",
             dir, root, root);
    int rc = system(cmd);
    snprintf(p, sizeof p, "%s/hidden.txt", dir);
    char *text = rc == 0 ? afile_read(p) : NULL;
    if (!text) {
        char why[2000];
        snprintf(p, sizeof p, "%s/hidden.log", dir);
        render_error(p, why, sizeof why);
        checklist_add(cl, VERDICT_FAIL, "paper render",
                      PATHS_MAIN_TEX " does not render with its generated values hidden: %s", why);
        return;
    }
    size_t bad = render_scan_text(text, PATHS_MAIN_TEX, cl);
    int pages = 0;
    for (const char *s = text; *s; s++) pages += *s == '\f';
    free(text);
    if (!bad && cl->n >= before)
        checklist_add(cl, VERDICT_PASS, "paper render",
                      PATHS_MAIN_TEX
                      " rendered by pdflatex with every generated value hidden (%d pages): no digit outside the names "
                      "of the experiments, W1, AVX2, AVX-512, SHA-256 and the simulation versions, and no verdict word",
                      pages);
}
