/**
 * Running DTRON from JUnit 5: {@link io.dtron.junit.DtronTest} on a method that takes a {@link
 * io.dtron.junit.DtronRun} tests the system it gets against a model, one test per seed and goal; on a method that
 * takes a {@link io.dtron.junit.DtronBusRun}, the systems behind the bus adapters it gets, in real time.
 */
package io.dtron.junit;
