/* tex_lex: TeX source read as TeX tokenizes it (design.md §9): the primitives
 * and command classes audit_tex.c reads the hand-written paper text with.
 * A reader takes the whole text s (NUL-terminated) and the index where it
 * starts, and returns the index after what it read. */
#ifndef TEX_LEX_H
#define TEX_LEX_H
#include <stddef.h>

/* The line (from 1) of text holding position pos. */
int tex_lex_line(const char *text, size_t pos);
/* Read "\name" at s[i] (letters and @, or one other character) into name
 * (cut to n - 1 characters); returns the end. */
size_t tex_lex_cs(const char *s, size_t i, char *name, size_t n);
/* The first index from i that is not white space. */
size_t tex_lex_space(const char *s, size_t i);
/* End of the balanced group opening at s[i] == open (index after the close;
 * an escaped open or close does not count); the text's end if unclosed. */
size_t tex_lex_group(const char *s, size_t i, char open, char close);
/* The letters spelled from s[i] up to \endcsname (spaces, braces and
 * \string ignored) into name; returns the index after \endcsname. */
size_t tex_lex_csname(const char *s, size_t i, char *name, size_t n);
/* LaTeX's own capitalised commands (\LaTeX, \Delta, \Bigl, ...): not claim macros. */
int tex_lex_latex_own(const char *name);
/* A command that defines the one after it (\newcommand, \def, \let, ...). */
int tex_lex_is_definer(const char *cmd);
/* A command that defines the name its {argument} spells (\@namedef, \csdef, ...). */
int tex_lex_is_namedef(const char *cmd);
/* A command whose next argument is a name, a file or a key, not text. */
int tex_lex_names_arg(const char *cmd);
/* Does s (after spaces) start with a TeX dimension unit (pt, em, \linewidth, ...)? */
int tex_lex_is_unit(const char *s);

#endif
