/* SPDX-License-Identifier: Apache-2.0 */
/* keeps the support library non-empty */
int modcp_test_support_empty(void);
int modcp_test_support_empty(void) { return 0; }
