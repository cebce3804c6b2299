/** The extension behind {@link io.dtron.junit.DtronTest}: not API. */
package io.dtron.junit.internal;
