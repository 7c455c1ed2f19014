/* Simulink S-function (Level 2, C MEX) around the dlw runtime estimator. Source only: it is not
 * compiled by the tests (that needs MATLAB). Build in MATLAB with
 *
 *   mex -I<repo>/crates/estimator-ffi/include sfun_dlw_estimator.c \
 *       <repo>/target/release/libdlw_estimator.a -lpthread -ldl
 *
 * Parameter 1: the estimator config's TOML text (a char row vector, e.g. fileread('fit.toml')).
 * Inputs: v1, v2 (V; v2 is ignored for a one-sensor config). Outputs: angle (deg), flags
 * (DLW_FLAG_* bits, as double). Discrete, at the block's sample time. */
#define S_FUNCTION_NAME sfun_dlw_estimator
#define S_FUNCTION_LEVEL 2

#include "simstruc.h"
#include "dlw_estimator.h"

static void mdlInitializeSizes(SimStruct *S) {
    ssSetNumSFcnParams(S, 1);
    if (ssGetNumSFcnParams(S) != ssGetSFcnParamsCount(S)) return;
    if (!ssSetNumInputPorts(S, 2)) return;
    ssSetInputPortWidth(S, 0, 1);
    ssSetInputPortWidth(S, 1, 1);
    ssSetInputPortDirectFeedThrough(S, 0, 1);
    ssSetInputPortDirectFeedThrough(S, 1, 1);
    if (!ssSetNumOutputPorts(S, 2)) return;
    ssSetOutputPortWidth(S, 0, 1);
    ssSetOutputPortWidth(S, 1, 1);
    ssSetNumSampleTimes(S, 1);
    ssSetNumPWork(S, 1);
    ssSetOptions(S, SS_OPTION_EXCEPTION_FREE_CODE);
}

static void mdlInitializeSampleTimes(SimStruct *S) {
    ssSetSampleTime(S, 0, INHERITED_SAMPLE_TIME);
    ssSetOffsetTime(S, 0, 0.0);
}

#define MDL_START
static void mdlStart(SimStruct *S) {
    static char error[512];
    char *config = mxArrayToString(ssGetSFcnParam(S, 0));
    DlwEstimator *e = NULL;
    if (config) {
        e = dlw_estimator_from_toml(config, error, sizeof error);
        mxFree(config);
    } else {
        snprintf(error, sizeof error, "parameter 1 must be the config's TOML text");
    }
    ssGetPWork(S)[0] = e;
    if (!e) ssSetErrorStatus(S, error);
}

static void mdlOutputs(SimStruct *S, int_T tid) {
    DlwEstimator *e = (DlwEstimator *)ssGetPWork(S)[0];
    double v1 = *ssGetInputPortRealSignalPtrs(S, 0)[0];
    double v2 = *ssGetInputPortRealSignalPtrs(S, 1)[0];
    double angle = 0.0;
    uint32_t flags = 0;
    if (dlw_estimator_step(e, v1, v2, &angle, &flags) != DLW_OK) {
        ssSetErrorStatus(S, "dlw_estimator_step failed");
        return;
    }
    ssGetOutputPortRealSignal(S, 0)[0] = angle;
    ssGetOutputPortRealSignal(S, 1)[0] = (double)flags;
    (void)tid;
}

static void mdlTerminate(SimStruct *S) {
    dlw_estimator_free((DlwEstimator *)ssGetPWork(S)[0]);
    ssGetPWork(S)[0] = NULL;
}

#ifdef MATLAB_MEX_FILE
#include "simulink.c"
#else
#include "cg_sfun.h"
#endif
