/**
 * Finding and launching an installed Uppaal TRON, for {@code dtron run MODEL --backend tron}.
 *
 * <p>DTRON cannot bundle TRON: TRON's licence forbids redistribution. {@link
 * io.dtron.troninstaller.TronInstallation} finds the executable ({@code TRON_HOME}, then {@code PATH}; {@code tron}
 * on Linux and macOS, {@code tron.exe} on Windows) and reads its version; {@link
 * io.dtron.troninstaller.TronLauncher} builds TRON's command line and runs it with commons-exec; {@link
 * io.dtron.troninstaller.TronOutput} reads the verdict and the seed from what TRON printed.
 */
package io.dtron.troninstaller;
