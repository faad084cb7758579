/* tex_lex: TeX source read as TeX tokenizes it, for the audit of the
 * hand-written paper text (design.md §9, audit_tex.c): a control sequence, a
 * balanced group, the name a \csname ... \endcsname spells, the line of a
 * position; and the classes of LaTeX commands that decide how the next token
 * is read (a definer, a command whose argument is a name, a dimension unit,
 * LaTeX's own capitalised commands). Limits: TeX's default category codes only
 * (the audit refuses \catcode); no verbatim; a name longer than its buffer is
 * cut; the command lists hold what the write-up can use, not all of LaTeX. */
#include "tex_lex.h"
#include <ctype.h>
#include <string.h>

int tex_lex_line(const char *text, size_t pos)
{
    int l = 1;
    for (size_t i = 0; i < pos && text[i]; i++) l += text[i] == '\n';
    return l;
}

size_t tex_lex_cs(const char *s, size_t i, char *name, size_t n)
{
    size_t k = 0, j = i + 1;
    if (!isalpha((unsigned char)s[j]) && s[j] != '@') { if (s[j]) { if (n > 1) { name[0] = s[j]; k = 1; } j++; } }
    else while (isalpha((unsigned char)s[j]) || s[j] == '@') { if (k + 1 < n) name[k++] = s[j]; j++; }
    name[k] = '\0';
    return j;
}

size_t tex_lex_space(const char *s, size_t i)
{
    while (s[i] && isspace((unsigned char)s[i])) i++;
    return i;
}

size_t tex_lex_group(const char *s, size_t i, char open, char close)
{
    int depth = 0;
    for (; s[i]; i++) {
        if (s[i] == '\\' && s[i + 1]) { i++; continue; }
        if (s[i] == open) depth++;
        else if (s[i] == close && --depth == 0) return i + 1;
    }
    return i;
}

size_t tex_lex_csname(const char *s, size_t i, char *name, size_t n)
{
    size_t k = 0;
    const char *e = strstr(s + i, "\\endcsname");
    size_t end = e ? (size_t)(e - s) : strlen(s);
    for (size_t j = i; j < end; j++) {
        if (s[j] == '\\') { char cs[32]; j = tex_lex_cs(s, j, cs, sizeof cs) - 1; continue; }
        if (isalpha((unsigned char)s[j]) && k + 1 < n) name[k++] = s[j];
    }
    name[k] = '\0';
    return e ? end + 10 : end;
}

/* Is name one of list's names (NULL-terminated)? Every command class is such a list. */
static int listed(const char *const *list, const char *name)
{
    for (int i = 0; list[i]; i++) if (!strcmp(list[i], name)) return 1;
    return 0;
}

/* LaTeX's own capitalised commands: not claim macros. */
static const char *latex_upper[] = {"LaTeX",
                                    "TeX",
                                    "Large",
                                    "LARGE",
                                    "Huge",
                                    "HUGE",
                                    "Roman",
                                    "Alph",
                                    "Ref",
                                    "S",
                                    "P",
                                    "L",
                                    "O",
                                    "AA",
                                    "AE",
                                    "OE",
                                    "Delta",
                                    "Gamma",
                                    "Theta",
                                    "Lambda",
                                    "Xi",
                                    "Pi",
                                    "Sigma",
                                    "Upsilon",
                                    "Phi",
                                    "Psi",
                                    "Omega",
                                    "Bigl",
                                    "Bigr",
                                    "Big",
                                    "Biggl",
                                    "Biggr",
                                    "bibliographystyle",
                                    "IfFileExists",
                                    NULL};

int tex_lex_latex_own(const char *name)
{
    return listed(latex_upper, name);
}

int tex_lex_is_definer(const char *cmd)
{
    static const char *defs[] = {"newcommand",
                                 "renewcommand",
                                 "providecommand",
                                 "def",
                                 "gdef",
                                 "edef",
                                 "xdef",
                                 "let",
                                 "DeclareRobustCommand",
                                 "NewDocumentCommand",
                                 "RenewDocumentCommand",
                                 "ProvideDocumentCommand",
                                 "DeclareDocumentCommand",
                                 "NewExpandableDocumentCommand",
                                 "newrobustcmd",
                                 "renewrobustcmd",
                                 "csdef",
                                 NULL};
    return listed(defs, cmd);
}

int tex_lex_is_namedef(const char *cmd)
{
    static const char *d[] = {"@namedef", "csdef",   "csgdef",         "csedef", "csxdef",
                              "cslet",    "csletcs", "NewCommandCopy", NULL};
    return listed(d, cmd);
}

int tex_lex_names_arg(const char *cmd)
{
    static const char *a[] = {"label",
                              "ref",
                              "eqref",
                              "pageref",
                              "autoref",
                              "cref",
                              "Cref",
                              "cite",
                              "citep",
                              "citet",
                              "nocite",
                              "includegraphics",
                              "input",
                              "include",
                              "InputIfFileExists",
                              "IfFileExists",
                              "subfile",
                              "usepackage",
                              "RequirePackage",
                              "documentclass",
                              "begin",
                              "end",
                              "url",
                              "href",
                              "fig",
                              "bibliography",
                              "bibliographystyle",
                              "includeonly",
                              "hypersetup",
                              "definecolor",
                              "textcolor",
                              "color",
                              "colorbox",
                              "newenvironment",
                              "renewenvironment",
                              "setcounter",
                              "addtocounter",
                              "pagestyle",
                              "thispagestyle",
                              "texttt",
                              NULL};
    return listed(a, cmd);
}

int tex_lex_is_unit(const char *s)
{
    static const char *u[] = {"pt",
                              "em",
                              "ex",
                              "cm",
                              "mm",
                              "in",
                              "bp",
                              "pc",
                              "dd",
                              "cc",
                              "sp",
                              "mu",
                              "fil",
                              "\\linewidth",
                              "\\textwidth",
                              "\\columnwidth",
                              "\\hsize",
                              "\\textheight",
                              "\\baselineskip",
                              "\\paperwidth",
                              NULL};
    while (*s == ' ') s++;
    for (int i = 0; u[i]; i++) {
        size_t n = strlen(u[i]);
        if (!strncmp(s, u[i], n) && (u[i][0] == '\\' || !isalpha((unsigned char)s[n]) || !strcmp(u[i], "fil")))
            return 1;
    }
    return 0;
}
