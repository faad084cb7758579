/* evalvol: the evaluation volumes; see evalvol.h. */
#include "evalvol.h"
#include <stdlib.h>
#include <string.h>

cs_status evalvol_of_eval(const char *eval, const char **name)
{
    static const char tail[] = " teacher stands per spacing";
    const char *t = eval ? strstr(eval, tail) : NULL;
    const char *b = t;
    while (b && b > eval && b[-1] >= '0' && b[-1] <= '9') b--;
    const long n = b && b < t ? strtol(b, NULL, 10) : -1;
    if (n == EVALVOL_SMALL_EVAL_STANDS) *name = EVALVOL_SMALL;
    else if (n == EVALVOL_LARGE_EVAL_STANDS) *name = EVALVOL_LARGE;
    else
        return cs_err(CS_EINPUT,
                      "evaluation line '%.80s': states neither volume's teacher stands per spacing (%d or %d)",
                      eval ? eval : "(none)", EVALVOL_SMALL_EVAL_STANDS, EVALVOL_LARGE_EVAL_STANDS);
    return CS_OK;
}
