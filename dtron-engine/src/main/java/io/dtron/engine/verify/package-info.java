/**
 * The model checker: {@link io.dtron.engine.verify.Verifier} checks {@link io.dtron.engine.verify.Query
 * queries} ({@code E<> p}, {@code A[] p}, {@code E[] p}, {@code A<> p}, {@code p --> q}) on a network by
 * symbolic exploration of its zone graph, with the engine's own semantics, and returns a {@link
 * io.dtron.engine.verify.VerificationResult} with statistics and, where one exists, a diagnostic {@link
 * io.dtron.engine.verify.Trace}.
 */
package io.dtron.engine.verify;
