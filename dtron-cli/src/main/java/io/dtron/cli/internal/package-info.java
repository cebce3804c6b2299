/** Not API: support classes of the {@code dtron} command line. */
package io.dtron.cli.internal;
